"""The driveline example's powertrain model (its FMU: fmu_src/Powertrain.py)."""
