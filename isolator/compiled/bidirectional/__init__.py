"""The bidirectional bearing as arrays for the compiled plan engine: the element
(:mod:`~isolator.compiled.bidirectional.bearing`, the same operations as
:mod:`isolator.bidirectional.element`) and the precise model's monitor grid held densely over
the reachable square (:mod:`~isolator.compiled.bidirectional.grid`)."""
