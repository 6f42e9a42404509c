"""Calls from one compiled function to another that do not compile the callee again.

numba links the machine code of every compiled function a compiled function calls into the
caller's own module, where LLVM optimises and emits it once more, and it types the callee before
it can type the caller. :func:`separately` gives a stand-in for a compiled function ``f``
(``jit`` or ``jit_unmanaged``) that compiled code calls instead: the call goes to an external
symbol named after ``f`` and the argument types, which :func:`bind` points at ``f``'s compiled
code in this process. The caller then compiles without ``f`` (in another process, at the same
time) and its machine code, cached on disk, holds only the call; the call itself is the one
numba makes (``f``'s native calling convention, not inlined), so it costs what it did.

A process must :func:`bind` ``f`` for the argument types of the call before it compiles or loads
the caller (else LLVM cannot resolve the symbol and ends the process). Called from Python the
stand-in calls ``f``; without numba it is ``f``.
"""

from __future__ import annotations

import hashlib
import inspect

from isolator.compiled.kernels import COMPILED

__all__ = ["bind", "bind_placeholder", "separately", "symbol_name"]

_BOUND: dict[str, int] = {}  # symbol -> address registered here (-1: a placeholder)


def symbol_name(function, argument_types, return_type) -> str:
    """The external symbol of ``function`` compiled for ``argument_types`` (numba types)
    returning ``return_type``: the function's module and name and a digest of the types."""
    python = getattr(function, "py_func", function)
    text = repr((str(return_type), tuple(str(t) for t in argument_types)))
    digest = hashlib.sha1(text.encode()).hexdigest()[:16]
    return f"dcfpb.{python.__module__}.{python.__qualname__}.{digest}"


if COMPILED:
    import llvmlite.binding as _llvm
    import numba
    from numba.core import cgutils, types
    from numba.core.extending import _Intrinsic

    class _SeparateCall(_Intrinsic):
        """numba's intrinsic that calls the external symbol; called from Python, the
        function itself (compiled again, with the wrapper and without the cache, when it was
        compiled without the wrapper for Python: :func:`isolator.compiled.kernels.jit_inner`)."""

        def __init__(self, function, return_type):
            self.function, self.return_type = function, return_type
            self._twin = None  # the function compiled with a wrapper, for calls from Python

            def typer(typingctx, *arguments):
                argument_types = tuple(types.unliteral(a) for a in arguments)
                symbol = symbol_name(function, argument_types, return_type)

                def codegen(context, builder, signature, values):
                    convention = context.call_conv
                    kind = convention.get_function_type(signature.return_type, signature.args)
                    callee = cgutils.get_or_insert_function(builder.module, kind, symbol)
                    convention.decorate_function(
                        callee, [f"arg{i}" for i in range(len(signature.args))],
                        signature.args)
                    status, result = convention.call_function(
                        builder, callee, signature.return_type, signature.args, values)
                    with cgutils.if_unlikely(builder, status.is_error):
                        convention.return_status_propagate(builder, status)
                    return result

                return return_type(*argument_types), codegen

            # numba reads the typer's parameters as the call's: name them as the function's
            names = list(inspect.signature(getattr(function, "py_func", function)).parameters)
            source = (f"def typer(typingctx, {', '.join(names)}):\n"
                      f"    return generic(typingctx, {', '.join(names)})\n")
            namespace = {"generic": typer}
            exec(source, namespace)  # the parameter names of our own function
            typer = namespace["typer"]
            python = getattr(function, "py_func", function)
            typer.__name__ = typer.__qualname__ = f"separately_{python.__name__}"
            super().__init__(typer.__name__, typer)
            self._register()

        def __call__(self, *arguments):
            function = self.function
            if function.targetoptions.get("no_cpython_wrapper"):  # not callable from Python:
                if self._twin is None:  # the same code with the wrapper, not cached
                    options = {key: value for key, value in function.targetoptions.items()
                               if key not in ("no_cpython_wrapper", "nopython")}
                    self._twin = numba.njit(**options)(function.py_func)
                function = self._twin
            return function(*arguments)

        def _reduce_states(self):
            raise TypeError("a separate call is not pickled")

    def separately(function, return_type):
        """A stand-in for the compiled ``function`` whose calls from compiled code go to the
        code :func:`bind` registers; ``return_type(numba.types)`` is its numba return type."""
        return _SeparateCall(function, return_type(types))

    def bind(call, argument_types) -> int:
        """Compile (or load from the cache) the function of the stand-in ``call`` for
        ``argument_types`` and register its code for the calls of compiled code; the address.
        Raises ``TypeError`` when it does not return the stand-in's return type."""
        argument_types = tuple(argument_types)
        symbol = symbol_name(call.function, argument_types, call.return_type)
        if _BOUND.get(symbol, 0) > 0:
            return _BOUND[symbol]
        call.function.compile(argument_types)
        result = call.function.overloads[argument_types]
        if result.signature.return_type != call.return_type:
            raise TypeError(f"{symbol}: returns {result.signature.return_type}, "
                            f"not {call.return_type}")
        address = result.library.get_pointer_to_function(result.fndesc.llvm_func_name)
        if not address:
            raise RuntimeError(f"{symbol}: no compiled code")
        _llvm.add_symbol(symbol, address)
        _BOUND[symbol] = address
        return address

    _PLACEHOLDER = []  # the C function a placeholder points at, kept alive

    def bind_placeholder(call, argument_types) -> None:
        """Register a placeholder for the stand-in ``call`` that ends the process (status 70)
        when called, so that a caller can be compiled and cached here before the function is:
        for a process that only compiles. Code compiled against it must never run, and a
        :func:`bind` after it does not mend code already compiled."""
        symbol = symbol_name(call.function, tuple(argument_types), call.return_type)
        if symbol in _BOUND:
            return
        import ctypes

        if not _PLACEHOLDER:
            import os

            _PLACEHOLDER.append(ctypes.CFUNCTYPE(None)(lambda: os._exit(70)))
        _llvm.add_symbol(symbol, ctypes.cast(_PLACEHOLDER[0], ctypes.c_void_p).value)
        _BOUND[symbol] = -1

else:  # pragma: no cover - without numba

    def separately(function, return_type):
        """Without numba: ``function`` itself."""
        return function

    def bind(call, argument_types) -> int:
        """Without numba: nothing to bind."""
        return 0

    def bind_placeholder(call, argument_types) -> None:
        """Without numba: nothing to bind."""
