"""Groups of arrays the compiled engine reads and writes without numba's reference counts.

numba counts the references of every array it hands on: each call that takes a group (the
heat history's 17 arrays, the work arrays, the building) or an array of it takes a reference
to each member at the call and drops it at the end, an atomic add apiece. Measured on the
engine of a building in plan (a 30 s pair, four bearings) these counts were about half of its
compiled time: ``perf`` put two instructions, the ``lock incq`` and ``lock decq`` of numba's
``NRT_incref`` / ``NRT_decref``, at 19 to 24 % of the whole process.

:func:`unmanaged` gives the same group with every member's memory-info pointer set to null,
which numba's counting functions skip (the arrays, their data, shapes and strides are the same,
the caller keeps the owners alive for the whole call). In plain Python, and in the Python
original of the engine, it returns its argument.
"""

from __future__ import annotations

from isolator.compiled import kernels

__all__ = ["unmanaged"]


def unmanaged(group):
    """``group`` (a tuple or NamedTuple of arrays) as the engine reads it: in compiled code,
    the same arrays without reference counting (module docstring); here, ``group`` itself."""
    return group


if kernels.COMPILED:  # pragma: no cover - depends on the environment
    from numba.core import cgutils, types
    from numba.extending import intrinsic, overload

    @intrinsic
    def _without_counts(typingctx, group):
        """The group with each array member's meminfo and parent set to null."""
        if not isinstance(group, types.BaseTuple) or not all(
                isinstance(member, types.Array) for member in group.types):
            return None

        def codegen(context, builder, signature, arguments):
            value = arguments[0]
            for index, member in enumerate(signature.args[0].types):
                array = context.make_array(member)(context, builder,
                                                   value=builder.extract_value(value, index))
                array.meminfo = cgutils.get_null_value(array.meminfo.type)
                array.parent = cgutils.get_null_value(array.parent.type)
                value = builder.insert_value(value, array._getvalue(), index)
            return value

        return group(group), codegen

    @overload(unmanaged)
    def _unmanaged(group):
        if isinstance(group, types.BaseTuple) and all(
                isinstance(member, types.Array) for member in group.types):
            return lambda group: _without_counts(group)
        return None
