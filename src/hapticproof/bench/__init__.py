"""Run time against error: the studies behind ``hapticproof bench`` and the benchmark scripts."""
