"""Robots of example-robot-data: lagmb beside Pinocchio and MuJoCo, a survey, a control loop (bench/README.md)."""
