"""The bridge to discrete-element (DEM) codes: the hereditary COR of a collision, the parameters of
each DEM contact law fitted to it with the error each law makes, COR tables, LAMMPS decks and Yade
scripts, and vcor's own contact law inside LAMMPS (a plugin, ``plugins/lammps/``).

:mod:`~vcor.dem.laws` (the DEM laws, their COR, the code version each needs), :mod:`~vcor.dem.fit`
(one collision's COR and every law fitted to it), :mod:`~vcor.dem.trend` (where a law's COR changes
with speed the other way from vcor's), :mod:`~vcor.dem.export` (the dataset, the table, the
parameters file), :mod:`~vcor.dem.lammps` (the decks of the fitted laws), :mod:`~vcor.dem.yade` (the
Yade script), :mod:`~vcor.dem.hereditary_law` (vcor's own law as the plugin takes it, its time step),
:mod:`~vcor.dem.mirror` (the COR LAMMPS computes with the plugin, without LAMMPS),
:mod:`~vcor.dem.hereditary` (its deck), :mod:`~vcor.dem.plugin` (building the plugin). The config's
``dem:`` block is checked and run by :mod:`vcor.study.dem`.
"""
