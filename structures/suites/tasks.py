"""The Dask side of a suite (:func:`structures.suites.suite.run_suite`): the cluster, and the
tasks, each a batch of runs of one record or pair computed and stored one by one; a batch redone
after its worker was lost keeps the runs it stored already (:func:`compute_and_store`).
"""

from __future__ import annotations

import os
import warnings
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from dcfpb.common.errors import InputError, InputTypeError, InputWarning
from dcfpb.common.validation import check_int
from isolator.limits import DEFAULT_MAX_STEPS
from structures.config import BuildingConfig
from structures.suites.runs import RunSpec, execute_run
from structures.suites.store import RunStore

SCHEDULER_TIMEOUT = 5.0
"""How long a scheduler address may take to answer as a Dask scheduler [s]
(:func:`check_scheduler`)."""

SCHEDULER_SCHEMES = ("tcp", "tls", "ws", "wss", "ucx", "inproc")
"""The address schemes of Dask's communications."""

HANDSHAKE_LIMIT = 1 << 20
"""The largest first message taken from a scheduler address [bytes]: a Dask scheduler's handshake
is a few hundred bytes; a larger length announced is garbage, refused before any allocation."""


def available_cores() -> int:
    """The CPU cores this process may run on (``os.sched_getaffinity``, else ``os.cpu_count``;
    at least 1)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        return max(1, os.cpu_count() or 1)


def capped_workers(n_workers: int | None, name: str = "n_workers",
                   owner: str = "local_cluster") -> int:
    """The local worker processes for ``n_workers`` (None: :func:`available_cores`), at most
    the cores available: more would only compete for them (and for memory). A larger number
    warns (:class:`~dcfpb.common.errors.InputWarning`) naming the parameter ``name``, the value
    and the cap."""
    cores = available_cores()
    if n_workers is None:
        return cores
    workers = check_int(n_workers, name, owner, low=1)
    if workers > cores:
        warnings.warn(InputWarning(
            f"{name} {workers} is more than the {cores} CPU core(s) available to this process: "
            f"the local cluster starts {cores} worker(s) (give a scheduler for more)."),
            stacklevel=3)
        return cores
    return workers


def local_cluster(n_workers: int | None = None) -> Any:
    """A ``distributed.LocalCluster`` of ``n_workers`` single-thread processes (default, and at
    most: the CPU cores available, :func:`capped_workers`) on the loopback interface, without a
    dashboard (the scheduler's HTTP server gets a free port instead of 8787, so suites side by
    side do not compete for it)."""
    from distributed import LocalCluster

    workers = capped_workers(n_workers)
    return LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                        host="127.0.0.1", dashboard_address=None,
                        scheduler_kwargs={"dashboard_address": "127.0.0.1:0"})


@contextmanager
def client_for(n_workers: int | None, scheduler_address: str | None) -> Iterator[Any]:
    """A Dask client of ``scheduler_address``, or of a new :func:`local_cluster` of
    ``n_workers``, closed with its cluster on leaving."""
    from distributed import Client

    if scheduler_address:
        address = check_scheduler(scheduler_address)
        try:
            client = Client(address, timeout=max(SCHEDULER_TIMEOUT, 1.0))
        except Exception as error:  # answered the probe, but not as a scheduler does
            reason = f"the Dask client could not connect: {error}"
            raise InputError(_scheduler_refusal("scheduler_address", scheduler_address,
                                                reason)) from error
        try:
            yield client
        finally:
            client.close()
        return
    cluster = local_cluster(n_workers)
    try:  # closed whatever happens, so that no worker process outlives the suite
        with Client(cluster) as client:
            yield client
    finally:
        cluster.close()


def _scheduler_refusal(name: str, address: str, reason: str) -> str:
    return (f"{name} {address!r}: {reason}; give the address of a running Dask scheduler, "
            "e.g. tcp://10.0.0.5:8786.")


def check_scheduler(address: object, name: str = "scheduler_address",
                    timeout: float | None = None) -> str:
    """``address``, checked to be a Dask scheduler that answers within ``timeout`` [s]
    (default :data:`SCHEDULER_TIMEOUT`).

    A ``tcp://host:port`` (or ``host:port``) address is probed before Dask connects: the
    connection must open and the first message must arrive within ``timeout`` and carry the
    length prefix of a Dask handshake (at most :data:`HANDSHAKE_LIMIT` bytes), so that a closed
    port, a server that accepts and says nothing (a plain HTTP server waits for a request) or one
    that sends something else is refused at once, without a hang or an allocation the size of
    whatever it sent. Other schemes (``tls://``, ``ws://``...) are left to Dask's own timeout.

    Raises
    ------
    dcfpb.common.errors.InputError
        Naming ``name`` (``--scheduler`` on the command line), the address and what went wrong.
    """
    import socket
    import struct

    timeout = SCHEDULER_TIMEOUT if timeout is None else timeout
    if not isinstance(address, str) or not address.strip():
        raise InputTypeError(_scheduler_refusal(name, str(address), "not an address"))
    address = address.strip()
    from distributed.comm.addressing import parse_address, parse_host_port

    try:
        scheme, location = parse_address(address if "://" in address else f"tcp://{address}")
        if scheme not in SCHEDULER_SCHEMES:
            raise ValueError(f"unknown scheme {scheme!r}, not one of {SCHEDULER_SCHEMES}")
        if scheme != "tcp":
            return address
        host, port = parse_host_port(location)
    except (ValueError, TypeError) as error:
        raise InputError(_scheduler_refusal(name, address, f"not a scheduler address "
                                            f"(tcp://HOST:PORT): {error}")) from None
    if not port:
        raise InputError(_scheduler_refusal(name, address, "no port given (tcp://HOST:PORT)"))
    try:
        sock = socket.create_connection((host, int(port)), timeout=timeout)
    except TimeoutError:
        raise InputError(_scheduler_refusal(
            name, address, f"nothing answers there within {timeout:g} s")) from None
    except OSError as error:
        reason = error.strerror or str(error) or type(error).__name__
        raise InputError(_scheduler_refusal(name, address, f"cannot connect ({reason})")) from None
    with sock:
        sock.settimeout(timeout)
        try:
            head = _receive(sock, 8)
            (length,) = struct.unpack("<Q", head) if len(head) == 8 else (0,)
            if len(head) < 8:
                reason = ("it closed the connection without a word" if not head else
                          f"it sent {len(head)} byte(s) and closed the connection")
            elif not 0 < length <= HANDSHAKE_LIMIT:
                reason = (f"it answered with something else than a Dask handshake (first "
                          f"bytes {head!r})")
            elif len(_receive(sock, length)) < length:
                reason = "it closed the connection in the middle of its first message"
            else:
                return address
        except TimeoutError:
            reason = (f"it accepted the connection but said nothing within {timeout:g} s "
                      "(a Dask scheduler greets at once)")
        except OSError as error:
            reason = f"the connection failed ({error.strerror or error})"
    raise InputError(_scheduler_refusal(name, address, f"not a Dask scheduler: {reason}"))


def _receive(sock: Any, size: int) -> bytes:
    """Up to ``size`` bytes from ``sock``, fewer when it closes first."""
    chunks, received = [], 0
    while received < size:
        chunk = sock.recv(min(size - received, 65536))
        if not chunk:
            break
        chunks.append(chunk)
        received += len(chunk)
    return b"".join(chunks)


DESIGN_MARK = ("isolator_displacement", "mu_max")
"""Keys of :func:`structures.analysis.design_peaks` whose presence in a stored row shows that
the row holds the design peaks (a row without them is computed again when they are asked)."""

BATCH_SIZE = 6
"""Runs of one ground motion handed to a worker as one task (see :func:`run_batch`)."""


def compute_and_store(spec: RunSpec, motion: Any, config: BuildingConfig,
                       out_dir: str, time_limit: float | None = None,
                       max_steps: int = DEFAULT_MAX_STEPS, storage: str = "full",
                       design: bool = False) -> dict[str, Any]:
    """The task of ``write="workers"``: compute a run and write its files where it ran, unless
    it is complete in the folder already (a batch redone after a lost worker); ``storage`` and
    ``design`` as :func:`~structures.suites.runs.execute_run` takes them."""
    store = RunStore(out_dir)
    row = store.completed_row(spec.run_id, storage, DESIGN_MARK if design else ())
    if row is not None:
        store.log_recovered([spec.run_id])
        return row
    row, data = execute_run(spec, motion, config, time_limit, max_steps, storage, design)
    return store.save_failure(row) if data is None else store.save_done(row, data)


def run_batch(task: Any, specs: list[RunSpec], motion: Any, config: BuildingConfig,
              *extra: Any) -> list[Any]:
    """One Dask task: ``task`` (:func:`compute_and_store`, or
    :func:`~structures.suites.runs.execute_run` when the client writes) of each run of one
    ground motion in turn, the motion read once for all (one that cannot be read is left to
    each run, which fails with the reader's reason)."""
    if motion is None:
        try:
            motion = specs[0].motion.read()
        except Exception:
            motion = None
    return [task(spec, motion, config, *extra) for spec in specs]


def batches(pending: list[RunSpec], size: int) -> list[list[RunSpec]]:
    """The pending runs grouped by ``spec.motion``, in chunks of at most ``size`` runs."""
    groups: dict[Any, list[RunSpec]] = {}
    for spec in pending:
        groups.setdefault(spec.motion, []).append(spec)
    return [group[i:i + size] for group in groups.values() for i in range(0, len(group), size)]
