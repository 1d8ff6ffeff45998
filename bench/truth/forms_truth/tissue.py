# SPDX-License-Identifier: LGPL-3.0-or-later
"""Baseline tissue: compressible neo-Hookean body (docs/MODEL.md eq. 5),

    E_tissue = int_B W(F) dV,  W = mu/2 (tr(F F^T) - 3 - 2 ln J) + lambda/2 (J - 1)^2.
"""
from .context import neo_hooke_density


class Term:
    def __init__(self, ctx):
        self.mu = ctx.constant(400.0)
        self.lmbda = ctx.constant(8000.0)
        self.density = neo_hooke_density(ctx.F, ctx.J, self.mu, self.lmbda)
        self.energy = self.density * ctx.dx

    def set(self, mu, lmbda):
        if not (mu > 0 and lmbda >= 0):
            raise ValueError(f"tissue: mu = {mu} Pa must be > 0 and lambda = {lmbda} Pa >= 0")
        self.mu.value = mu
        self.lmbda.value = lmbda
