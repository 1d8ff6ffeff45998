# SPDX-License-Identifier: LGPL-3.0-or-later
"""Equilibrium of the truth model: minimise the total energy
Pi(u) = E_tissue + E_gravity + sum E_effects over P2 displacements with

    u_x = 0 on the symmetry face (sliding, docs/MODEL.md),
    u = 0 on the base unless an effect replaces the fixed base by springs
    (or u_y = 0 only, fixed_base = "normal": a base that slides along the chest),

by Newton's method (residual R = dPi/du, Jacobian dR/du, MUMPS via PETSc)
with a backtracking line search on Pi and a ramp of the gravity load factor
(halved on failure, doubled on success).
"""
import time

import numpy as np
import ufl
from dolfinx import fem
import dolfinx.fem.petsc  # noqa: F401  (registers fem.petsc)
from petsc4py import PETSc

from geometry import TAGS

# GMRES iterations with the factors of an older Jacobian before refactoring:
# one MUMPS factorisation costs about as much as 20-30 preconditioned
# iterations; beyond 10 the old factors are too far off to be worth it.
MAX_KRYLOV = 10
# Newton iterations allowed per posture solve before giving up.
MAX_NEWTON = 60


class SolveError(RuntimeError):
    pass


class TruthModel:
    def __init__(self, ctx, tissue, gravity, effects, fixed_base, rtol=1e-9):
        self.ctx, self.tissue, self.gravity = ctx, tissue, gravity
        u, v, du = ctx.u, ctx.v, ctx.du
        energy = tissue.energy + gravity.energy
        for e in effects:
            energy = energy + e.energy
        residual = ufl.derivative(energy, u, v)
        self.energy_form = fem.form(energy)
        self.residual_form = fem.form(residual)
        self.jacobian_form = fem.form(ufl.derivative(residual, u, du))
        self.bcs = self._boundary_conditions(fixed_base)
        self.rtol = rtol
        self.A = fem.petsc.create_matrix(self.jacobian_form)
        self.b = fem.petsc.create_vector(self.residual_form)
        self.du = fem.Function(ctx.V)
        self.P = None                 # the Jacobian whose factors precondition
        self.ksp = PETSc.KSP().create(ctx.mesh.comm)
        self.ksp.setType("gmres")
        self.ksp.setTolerances(rtol=1e-10, atol=0.0, max_it=MAX_KRYLOV)
        self.ksp.setGMRESRestart(MAX_KRYLOV)
        pc = self.ksp.getPC()
        pc.setType("cholesky")        # the Jacobian of an energy is symmetric
        pc.setFactorSolverType("mumps")
        self.stats = {"newton": 0, "factorizations": 0, "krylov": 0, "seconds": 0.0}

    def _boundary_conditions(self, fixed_base):
        ctx = self.ctx
        fdim = ctx.mesh.topology.dim - 1
        sym = ctx.facet_tags.find(TAGS["symmetry"])
        dofs_x = fem.locate_dofs_topological(ctx.V.sub(0), fdim, sym)
        bcs = [fem.dirichletbc(PETSc.ScalarType(0), dofs_x, ctx.V.sub(0))]   # u_x = 0
        if fixed_base == "normal":                                          # u_y = 0 on the base
            base = ctx.facet_tags.find(TAGS["base"])
            dofs_y = fem.locate_dofs_topological(ctx.V.sub(1), fdim, base)
            bcs.append(fem.dirichletbc(PETSc.ScalarType(0), dofs_y, ctx.V.sub(1)))
        elif fixed_base:
            base = ctx.facet_tags.find(TAGS["base"])
            dofs = fem.locate_dofs_topological(ctx.V, fdim, base)
            bcs.append(fem.dirichletbc(np.zeros(3, dtype=PETSc.ScalarType), dofs, ctx.V))
        return bcs

    # -- assembly -----------------------------------------------------------
    def _residual(self):
        """R(u) with the Dirichlet rows set to u - g (= 0 when u satisfies them)."""
        with self.b.localForm() as loc:
            loc.set(0.0)
        fem.petsc.assemble_vector(self.b, self.residual_form)
        self.b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        fem.petsc.set_bc(self.b, self.bcs, x0=self.ctx.u.vector, scale=-1.0)
        return self.b.norm()

    def _jacobian(self):
        self.A.zeroEntries()
        fem.petsc.assemble_matrix(self.A, self.jacobian_form, bcs=self.bcs)
        self.A.assemble()

    def _energy(self):
        return fem.assemble_scalar(self.energy_form)

    def _refactor(self):
        if self.P is None:
            self.P = self.A.duplicate(copy=True)
        else:
            self.A.copy(self.P, structure=PETSc.Mat.Structure.SAME_NONZERO_PATTERN)
        self.ksp.setOperators(self.A, self.P)
        self.stats["factorizations"] += 1

    def _linear_solve(self):
        """J du = -R by GMRES preconditioned with the MUMPS factors of an earlier
        Jacobian P (exact after one iteration when P = J); P is refactored
        from the current J when GMRES does not converge in MAX_KRYLOV steps."""
        if self.P is None:
            self._refactor()
        self.ksp.setOperators(self.A, self.P)
        self.ksp.solve(self.b, self.du.vector)
        self.stats["krylov"] += self.ksp.getIterationNumber()
        if self.ksp.getConvergedReason() <= 0:
            self._refactor()
            self.ksp.solve(self.b, self.du.vector)
            self.stats["krylov"] += self.ksp.getIterationNumber()
            if self.ksp.getConvergedReason() <= 0:
                raise SolveError(f"linear solve failed (reason {self.ksp.getConvergedReason()})")
        self.du.x.scatter_forward()

    # -- Newton -------------------------------------------------------------
    def newton(self, atol, max_it=30):
        """Newton iterations at the current load; True when ||R|| <= atol."""
        u = self.ctx.u
        res = self._residual()
        if not np.isfinite(res):
            return False
        e_old = self._energy()
        for _ in range(max_it):
            if res <= atol:
                return True
            self._jacobian()
            self.b.scale(-1.0)
            self._linear_solve()                      # J du = -R
            self.stats["newton"] += 1
            u0 = u.x.array.copy()
            alpha, accepted = 1.0, False
            for _ls in range(8):                      # backtracking on Pi
                u.x.array[:] = u0 + alpha * self.du.x.array
                e_new = self._energy()
                res_new = self._residual()
                # accept a decrease of Pi, or an Armijo decrease of ||R||
                if np.isfinite(e_new) and np.isfinite(res_new) and (
                        e_new <= e_old + 1e-12 * abs(e_old) or res_new <= (1 - 1e-4 * alpha) * res):
                    accepted = True
                    break
                alpha *= 0.5
            if not accepted:
                u.x.array[:] = u0
                return False
            e_old, res = e_new, res_new
        return res <= atol

    def load_norm(self):
        """||R(0)|| at full load: the scale of the Newton tolerance."""
        u = self.ctx.u
        saved = u.x.array.copy()
        u.x.array[:] = 0.0
        self.gravity.load.value = 1.0
        n = self._residual()
        u.x.array[:] = saved
        return n

    def solve_posture(self, theta_deg, rho, start=None, min_step=1.0 / 64, budget=MAX_NEWTON):
        """Equilibrium in posture theta; from `start` (array) at full load if
        given (falls back to the ramp from the neutral state), else ramped.
        Gives up (SolveError) below `min_step` or after `budget` Newton
        iterations (e.g. a crease at the fold of a very soft breast)."""
        t0 = time.perf_counter()
        n0 = self.stats["newton"]
        self.gravity.set_posture(theta_deg, rho)
        atol = self.rtol * self.load_norm()
        u = self.ctx.u
        if start is not None:
            u.x.array[:] = start
            self.gravity.load.value = 1.0
            if self.newton(atol):
                self.stats["seconds"] += time.perf_counter() - t0
                return u.x.array.copy()
        u.x.array[:] = 0.0
        level, step, saved = 0.0, 1.0, u.x.array.copy()
        while level < 1.0:
            target = min(1.0, level + step)
            self.gravity.load.value = target
            if self.newton(atol):
                level, saved = target, u.x.array.copy()
                step = min(2 * step, 1.0)
            else:
                u.x.array[:] = saved
                step /= 2
                if self.stats["newton"] - n0 > budget:
                    raise SolveError(f"posture theta = {theta_deg} deg: no convergence within "
                                     f"{budget} Newton iterations (load {level:.4f} reached)")
                if step < min_step:
                    raise SolveError(f"posture theta = {theta_deg} deg: no convergence at load "
                                     f"{target:.4f} (step {2 * step:.2e})")
        self.stats["seconds"] += time.perf_counter() - t0
        return u.x.array.copy()
