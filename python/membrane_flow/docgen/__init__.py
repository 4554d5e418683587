"""Generators of the pages of docs/ that are made from runs or from the code: the parameter manual,
the experiments, the gallery, the parameter studies and the branches."""
