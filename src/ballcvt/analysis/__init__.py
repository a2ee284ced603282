"""Workflows on top of the solvers: sweeps and maps, tables, duty cycles, design studies,
fluid fitting and the reproduction of the paper. They take a drive and solver options,
never the public API object."""
