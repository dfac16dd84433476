"""The bridge to discrete-element (DEM) codes: the hereditary COR of a collision, the parameters of
each DEM contact law fitted to it with the error each law makes, COR tables, LAMMPS decks and Yade
scripts.

:mod:`~vcor.dem.laws` (the DEM laws, their COR, the code version each needs), :mod:`~vcor.dem.fit`
(one collision's COR and every law fitted to it), :mod:`~vcor.dem.trend` (where a law's COR changes
with speed the other way from vcor's), :mod:`~vcor.dem.export` (the dataset, the table, the
parameters file), :mod:`~vcor.dem.lammps` (the decks), :mod:`~vcor.dem.yade` (the Yade script). The
config's ``dem:`` block is checked and run by :mod:`vcor.study.dem`.
"""
