"""Decisions about systems: positive realness (symbolic and the numeric fast path), design
answers, stability boundaries, sampled-data loops, maps, simulation, n-port networks."""
