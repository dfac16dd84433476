"""From measured data to materials: Prony and CERF fits, DMA files and time-temperature
superposition, calibration from measured COR."""
