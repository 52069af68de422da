"""Exact algebra and decisions: real-root isolation, the decision kernel, unit-circle and
trigonometric forms, constant and polynomial matrices, canonical forms -- and, beside them, the
independent certificate checker, which imports none of them."""
