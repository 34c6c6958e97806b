"""The driveline example's powertrain model (its FMU: build/Powertrain.fmu, mounts.py compiled)."""
