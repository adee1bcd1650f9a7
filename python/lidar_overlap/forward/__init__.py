"""The overlap function: methods (RT, FO, Auto, Turbulent), the plan that decides a computation, the
backends that run it (the only callers of the core's compute functions) and the result."""
