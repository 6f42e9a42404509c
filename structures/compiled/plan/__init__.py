"""The compiled engine of the building in plan (:func:`structures.spatial.analysis.run_spatial`
with ``engine="compiled"`` or ``"auto"``): the time loop as one numba function
(:mod:`~structures.compiled.plan.integrator`, its numerical pieces in
:mod:`~structures.compiled.plan.linear`), the layout of its arrays
(:mod:`~structures.compiled.plan.workspace`), the groups it reads without reference counts
(:mod:`~structures.compiled.plan.unmanaged`) and the adapter that packs the model and returns
the reference's histories (:mod:`~structures.compiled.plan.engine`). The bidirectional bearing
it calls is :mod:`isolator.compiled.bidirectional.bearing`. A numba function of its own: the planar
engine
and ``dcfpb demo`` never compile it."""
