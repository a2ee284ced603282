"""The published physics as pure functions: geometry and kinematics, contact mechanics,
traction laws, clamping laws, loss terms, operating modes and architectures.

Imports only `ballcvt.params` and the leaves (`ballcvt.errors`, `ballcvt.units`).
"""
