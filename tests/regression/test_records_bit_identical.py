"""Records read correctly before issue 22 read bit-identically after it: the bundled El Centro
and every record of ``../shared/groundmotions`` (the suite, the header variants and the pairs),
their time step, count and the SHA-256 of their acceleration array's bytes [m/s^2, float64,
little-endian], pinned from the reader as it stood before the unit, step and plausibility
checks of issue 22.
"""

from __future__ import annotations

import hashlib
import sys

import pytest

from groundmotions import load_bundled
from groundmotions.readers import read_record

pytestmark = pytest.mark.skipif(sys.byteorder != "little", reason="hashes of little-endian bytes")

_PINNED_TEXT = """
bundled 0.02 1559 e6f1610e1ee08ef0cb4103ca
A-BEN360.AT2 0.005 7996 19bd51d1a078dc86ab072a05
A-BPL160.AT2 0.005 7996 562528992bf742982242474a
A-ELC180.AT2 0.01 4000 2168b3c2805e4f2752a54b6a
A-LAD180.AT2 0.005 7996 8521d56c6240937cbf871bf9
A-LVD000.AT2 0.005 4396 c69d725ffb5ce2a4cca44783
A-LVL090.AT2 0.005 4396 59e97db9933c02eea2b8d10c
A-MAM290.AT2 0.005 7996 2d877b5b56b733cba3f026ab
A-PAS180.AT2 0.005 12053 657dbedf0e8406acc2e75828
A-PEL180.AT2 0.005 10087 d131ccc7ab3702d949acfb60
A-SHE009.AT2 0.005 7996 bc466938e4e5c008aa100d97
A-SON303.AT2 0.005 8000 f25c37dbe13695ca960266d8
A-TIN000.AT2 0.005 7996 92c732f446da9eaa88b26018
A-ZAK360.AT2 0.005 7996 633f3d4ddd5ebebbba94daf3
ANLA196.AT2 0.02 1451 7fa319fbd1d000b1acd539f3
ANLCSOU.AT2 0.02 1215 63e35bf18230a71b2f8dd916
AZF225.AT2 0.005 2060 9d59588267693c3b8644159c
B-BEN360.AT2 0.005 7993 9ea65cd248d40f037b4c7b3d
B-ELC000.AT2 0.005 8000 12035251e6498071a50698c1
B-LAD180.AT2 0.005 7984 2f56974758071ef134452e2b
B-SHE009.AT2 0.005 7999 82f769cfe46b0ed2ba9d938c
B-ZAK360.AT2 0.005 7973 d98c0973e9758531ab0cca45
BAR315.AT2 0.005 2056 97dc71c686f4c6cbfcd1d34a
D-ZAK360.AT2 0.005 7973 f554646106c3fbe5d1975e3b
EIL-EW.AT2 0.005 12000 a6c4436cb993cba8829226c9
EUR090.AT2 0.02 2200 aff4a7aef971a2a34643a71c
FOR090.AT2 0.02 2200 60380e60c55b417b4d8ed818
GCN-WE.AT2 0.00244 8192 dbee440a26c98ad709ddc31c
HAD-NS.AT2 0.005 12000 a29dd397f6865bdbd9986598
HAU000.AT2 0.005 5600 e92db9d086571b963cc4abae
HEN-E.AT2 0.005 12000 04c863b472db19c9f54c436f
HOS180.AT2 0.01 10000 bc9114863a4be304249be01f
HWA002-N.AT2 0.004 20000 6bce9407c1abb670e87b03dc
HWA012-N.AT2 0.005 17601 53b17ab36bb56fddcefe9fd2
HWA013-N.AT2 0.005 18000 f4c7083ae451b90befc37559
HWA017-N.AT2 0.005 17401 57050f900c62a8d1fd67a242
HWA036-N.AT2 0.005 18000 9e9a5cef34c892706b338982
HWA037-N.AT2 0.005 18000 2d2c99d2d6db6b6c9c9a74a7
HWA053-N.AT2 0.004 20750 d81fde57dec32ad609ae25dd
HWA058-N.AT2 0.005 18000 3e298ed0a7a9d665a79d1709
ISE-WE.AT2 0.00244 6557 b5c50965c903c49f9aac8081
KAU008-N.AT2 0.005 18000 d1ac9cf6deb9df01ab09422e
KAU020-N.AT2 0.005 18000 10042c32033a0224a11dd64b
KAU030-N.AT2 0.005 18000 07fd14dcba9c35b37217d18c
KAU046-N.AT2 0.005 18000 ca2a0cbe54a3cb2cdd7f302e
KAU054-N.AT2 0.005 18000 e7e7e4bed2b2fbe0e1957cef
KAU057-N.AT2 0.005 17800 0a4d6031f85485052880401e
KAU082-N.AT2 0.005 17800 740e40aef016b28f27976c13
KAU086-N.AT2 0.004 27500 93b47a623db5c0923d1ad346
NSK-E.AT2 0.005 9200 396ff3f688128410a85e5f5e
NST-N.AT2 0.005 12000 5873f654d35c6e9d1c25148c
PBFEAS.AT2 0.01 2364 08519e1165469e76ba2ec24d
PFT135.AT2 0.005 2062 cebce9076a5d4f6c44a0e9f6
RIO270.AT2 0.02 1800 a2d57199faff9d615363f79f
ROC-NS.AT2 0.00244 8192 fda377ec670dc716183a96c7
SGL-E.AT2 0.005 10400 c4f8fda3c6ae5dcca1d7c307
SHL000.AT2 0.02 1800 5dabe541ba57b21baf8b437e
SSD-E.AT2 0.005 12000 ba443a49b9564a50f7c46ea6
WGK-N.AT2 0.005 11800 c95191e8f403dd29c4ff7a73
WTC-E.AT2 0.005 12000 113e0f6976a6945974f57526
elCentro.AT2 0.02 1559 e6f1610e1ee08ef0cb4103ca
pairs/CHY023-N.AT2 0.004 37000 3a168e2069e28c25b9b812bb
pairs/CHY023-W.AT2 0.004 37000 525e1f5239c76d30939936b9
pairs/ILA061-N.AT2 0.004 23000 856e31c100cfd6003dad9c0c
pairs/ILA061-W.AT2 0.004 23000 0fc47c4e47d8b90896829c6c
pairs/TAP084-N.AT2 0.004 27000 8514d5a40c92fb84c6981455
pairs/TAP084-W.AT2 0.004 27000 1d4e821330474778629d2ceb
pairs/TAP094-E.AT2 0.005 23600 af4fce07f9a91d3eaba291fd
pairs/TAP094-N.AT2 0.005 23600 32efaae38f872c4aa88d3ae1
variants/EXAMPLES_ExampleScripts_ARL360.at2 0.02 2000 cf17ba2fa5dbf028530ac37a
variants/EXAMPLES_verification_elCentro.at2 0.02 1559 e6f1610e1ee08ef0cb4103ca
variants/Workshops_OpenSeesDays_Steel2dModels_Oak_2_50_5_FN.AT2 0.005 7997 1e4c0dd4ae06469a6501ae50
"""
PINNED: dict[str, tuple[float, int, str]] = {
    name: (float(dt), int(npts), digest)
    for name, dt, npts, digest in (line.split() for line in _PINNED_TEXT.strip().splitlines())
}
"""Record (``bundled`` or a path under ``../shared/groundmotions``) -> (dt [s], npts, first 24
hex digits of the SHA-256 of the acceleration's bytes)."""


def _digest(motion) -> tuple[float, int, str]:
    return motion.dt, motion.npts, hashlib.sha256(motion.acceleration.tobytes()).hexdigest()[:24]


def test_the_bundled_record_reads_bit_identically():
    assert _digest(load_bundled()) == PINNED["bundled"]


@pytest.mark.shared
@pytest.mark.parametrize("name", sorted(set(PINNED) - {"bundled"}))
def test_every_shared_record_reads_bit_identically(shared_dir, name):
    assert _digest(read_record(shared_dir / "groundmotions" / name)) == PINNED[name]
