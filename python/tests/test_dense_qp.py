"""walkgen.DenseQp from NumPy: known solutions, KKT conditions, warm start, errors."""

import math

import numpy as np
import pytest

import walkgen


def kkt(H, g, A, lb, ub, l, u, r):
    """Largest violation of the KKT conditions of r (the sign convention of dense_qp.hpp)."""
    x, y, z = r.x, r.y, r.z
    stationarity = np.abs(H @ x + g + A.T @ y + z).max()
    Ax = A @ x
    primal = max(np.max(lb - Ax, initial=0), np.max(Ax - ub, initial=0),
                 np.max(l - x, initial=0), np.max(x - u, initial=0))
    # y_i <= 0 where the lower side is active, >= 0 where the upper side is, 0 where inactive.
    slack_rows = np.where(y < 0, Ax - lb, np.where(y > 0, ub - Ax, 0.0))
    slack_bounds = np.where(z < 0, x - l, np.where(z > 0, u - x, 0.0))
    complementarity = max(np.abs(y * slack_rows).max(initial=0),
                          np.abs(z * slack_bounds).max(initial=0))
    return max(stationarity, primal, complementarity)


def random_qp(rng, n, m):
    M = rng.standard_normal((n, n))
    H = M @ M.T + n * np.eye(n)
    g = rng.standard_normal(n)
    A = rng.standard_normal((m, n))
    centre = A @ rng.uniform(-0.5, 0.5, n)  # a point inside l <= x <= u: feasible
    lb = centre - rng.uniform(0.1, 1.0, m)
    ub = centre + rng.uniform(0.1, 1.0, m)
    l = -np.ones(n)
    u = np.ones(n)
    return H, g, A, lb, ub, l, u


def test_unconstrained_minimum_is_minus_h_inverse_g():
    H = np.array([[4.0, 1.0], [1.0, 3.0]])
    g = np.array([1.0, 2.0])
    qp = walkgen.DenseQp(2)
    r = qp.solve(H, g)
    assert r.status == "solved" and r.ok
    np.testing.assert_allclose(r.x, np.linalg.solve(H, -g), atol=1e-12)
    assert r.objective == pytest.approx(0.5 * r.x @ H @ r.x + g @ r.x, abs=1e-12)


def test_active_bound_gives_the_projected_solution_and_its_multiplier():
    # min ½|x - (2, 0)|²  s.t.  x0 <= 1  ->  x = (1, 0), z0 = 1 (upper side, >= 0)
    qp = walkgen.DenseQp(2)
    r = qp.solve(np.eye(2), np.array([-2.0, 0.0]), u=np.array([1.0, np.inf]))
    np.testing.assert_allclose(r.x, [1.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(r.z, [1.0, 0.0], atol=1e-12)
    assert r.active_set_size == 1


def test_equality_row_projects_onto_the_line():
    # min ½|x|²  s.t.  x0 + x1 = 1  ->  x = (½, ½), y = -½ ... sign: Hx + Aᵀy = 0 -> y = -½
    qp = walkgen.DenseQp(2, 1)
    r = qp.solve(np.eye(2), np.zeros(2), np.array([[1.0, 1.0]]), np.array([1.0]),
                 np.array([1.0]))
    np.testing.assert_allclose(r.x, [0.5, 0.5], atol=1e-12)
    np.testing.assert_allclose(r.y, [-0.5], atol=1e-12)


@pytest.mark.parametrize("seed", range(5))
def test_random_qps_meet_their_kkt_conditions(seed):
    rng = np.random.default_rng(seed)
    H, g, A, lb, ub, l, u = random_qp(rng, 12, 8)
    r = walkgen.DenseQp(12, 8).solve(H, g, A, lb, ub, l, u)
    assert r.status == "solved"
    assert kkt(H, g, A, lb, ub, l, u, r) < 1e-9
    assert r.dual_residual < 1e-9 and r.primal_residual < 1e-9


def test_infeasible_problem_is_a_status_not_an_exception():
    qp = walkgen.DenseQp(1, 2)
    A = np.array([[1.0], [1.0]])
    r = qp.solve(np.eye(1), np.zeros(1), A, np.array([1.0, -np.inf]), np.array([np.inf, 0.0]))
    assert r.status == walkgen.QpStatus.infeasible
    assert str(r.status) == "infeasible" and not r.ok


def test_update_reuses_the_factorisation_and_warm_start():
    rng = np.random.default_rng(7)
    H, g, A, lb, ub, l, u = random_qp(rng, 10, 6)
    qp = walkgen.DenseQp(10, 6)
    first = qp.solve(H, g, A, lb, ub, l, u)
    assert first.ok
    g2 = g + 1e-3 * rng.standard_normal(10)
    qp.update(g=g2)
    second = qp.solve()
    assert second.ok and second.warm_started
    cold = walkgen.DenseQp(10, 6).solve(H, g2, A, lb, ub, l, u)
    np.testing.assert_allclose(second.x, cold.x, atol=1e-10)
    assert kkt(H, g2, A, lb, ub, l, u, second) < 1e-9


def test_reset_warm_start_gives_a_cold_solve():
    rng = np.random.default_rng(3)
    H, g, A, lb, ub, l, u = random_qp(rng, 6, 4)
    qp = walkgen.DenseQp(6, 4)
    qp.solve(H, g, A, lb, ub, l, u)
    qp.reset_warm_start()
    assert not qp.solve(H, g, A, lb, ub, l, u).warm_started


def test_results_are_copies_that_outlive_the_next_solve():
    qp = walkgen.DenseQp(2)
    r1 = qp.solve(np.eye(2), np.array([1.0, 0.0]))
    x1 = r1.x.copy()
    qp.solve(np.eye(2), np.array([-5.0, 3.0]))
    np.testing.assert_array_equal(r1.x, x1)


def test_lists_and_integer_arrays_are_accepted():
    r = walkgen.DenseQp(2).solve([[2, 0], [0, 2]], [2, -4])
    np.testing.assert_allclose(r.x, [-1.0, 2.0])


@pytest.mark.parametrize("H, g, message", [
    (np.eye(3), np.zeros(2), "DenseQp.solve: H: expected a matrix of shape (2, 2), got shape (3, 3)"),
    (np.eye(2), np.zeros(3), "DenseQp.solve: g: expected a vector of shape (2,), got shape (3,)"),
    (np.eye(2), np.array(["a", "b"]), "DenseQp.solve: g: expected an array of real numbers"),
    (np.eye(2) * 1j, np.zeros(2), "DenseQp.solve: H: expected an array of real numbers"),
])
def test_wrong_shapes_and_dtypes_raise_value_error(H, g, message):
    with pytest.raises(ValueError) as error:
        walkgen.DenseQp(2).solve(H, g)
    assert message in str(error.value)


def test_nan_and_indefinite_data_raise_value_error_with_the_solver_message():
    qp = walkgen.DenseQp(2)
    with pytest.raises(ValueError, match="DenseQp.solve"):
        qp.solve(np.eye(2), np.array([math.nan, 0.0]))
    with pytest.raises(ValueError, match="positive definite"):
        qp.solve(np.diag([1.0, -1.0]), np.zeros(2))
    with pytest.raises(ValueError, match="lb"):
        walkgen.DenseQp(1, 1).solve(np.eye(1), np.zeros(1), np.eye(1), np.array([1.0]),
                                    np.array([0.0]))


def test_missing_rows_and_bad_sizes_raise():
    with pytest.raises(ValueError, match="A: expected a matrix of shape \\(1, 2\\), got None"):
        walkgen.DenseQp(2, 1).solve(np.eye(2), np.zeros(2))
    with pytest.raises(ValueError, match="num_vars"):
        walkgen.DenseQp(0)
    with pytest.raises(ValueError, match="update\\(\\) needs a successful init"):
        walkgen.DenseQp(2).update(g=np.zeros(2))


def test_settings_are_checked():
    s = walkgen.QpSettings()
    s.regularization = -1.0
    with pytest.raises(ValueError, match="regularization"):
        walkgen.DenseQp(2, 0, s)
    qp = walkgen.DenseQp(2)
    with pytest.raises(ValueError, match="regularization"):
        qp.settings = s
