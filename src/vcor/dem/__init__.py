"""The bridge to discrete-element (DEM) codes: the hereditary COR of a collision, the parameters of
each DEM contact law fitted to it with the error each law makes, COR tables, and LAMMPS decks.

:mod:`~vcor.dem.laws` (the DEM laws and their COR), :mod:`~vcor.dem.fit` (one collision's COR and
every law fitted to it), :mod:`~vcor.dem.spec` (the config's ``dem:`` block, checked before any
job), :mod:`~vcor.dem.export` (the dataset, the table), :mod:`~vcor.dem.lammps` (the decks).
"""
