"""The model of the loop: a device, a wall and the catalogue, in physical units with their dimensionless groups.

- :mod:`~dfa.model.device`: :class:`~dfa.model.device.Device` (m, b, c, Δ, T) and its groups
  :class:`~dfa.model.device.Params` (μ, β, σ, paper Table 1);
- :mod:`~dfa.model.wall`: the virtual wall rendered on it (spring, damper, velocity filter, delay,
  amplifier lag) and its groups;
- :mod:`~dfa.model.catalogue`: the devices of paper Table 2 and the resolution of user inputs;
- :mod:`~dfa.model.units`: physical units of the quantities the analyses return.

Every analysis (:mod:`dfa.analysis`) takes these objects; nothing here analyses anything.
"""
