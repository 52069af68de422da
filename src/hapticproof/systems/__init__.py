"""What is analysed: scenes and scene files, device models and G^-1(z), discretisation,
m users, teleoperators, impedances and the sampled-data loops they form."""
