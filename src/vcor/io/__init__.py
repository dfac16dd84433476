"""Files in and out: CSV tables whose errors name the file, line and column; NetCDF datasets with
CF metadata and provenance; the per-scene manifest."""
