"""coulomb.ContactProblem and coulomb.Block: construction from NumPy, properties, round trips."""
import pickle

import numpy as np
import pytest

import coulomb


def two_contacts():
    """Two contacts with a coupling block between them, W symmetric positive definite."""
    rng = np.random.default_rng(7)
    A = rng.normal(size=(6, 6))
    W = A @ A.T + 6 * np.eye(6)
    q = np.array([-1.0, 0.2, -0.1, -0.5, 0.0, 0.3])
    return W, q, np.array([0.5, 0.8])


def test_dense_problem_properties():
    W, q, mu = two_contacts()
    p = coulomb.ContactProblem(W, q, mu, name="two")
    assert p.size == 6 and p.contact_count == 2 and p.block_count == 2
    assert p.name == "two" and p.storage == "dense"
    np.testing.assert_array_equal(p.W, W)
    np.testing.assert_array_equal(p.q, q)
    np.testing.assert_array_equal(p.mu, mu)
    assert [b.kind for b in p.blocks] == ["contact", "contact"]
    assert p.warm_start is None
    assert "6 unknowns, 2 contacts" in repr(p)


def test_integer_arrays_are_converted():
    p = coulomb.ContactProblem(np.eye(3, dtype=int), [-1, 0, 0], [1])
    assert p.W.dtype == np.float64 and p.q[0] == -1.0


def test_triplets_sum_duplicates_and_keep_the_matrix():
    W, q, mu = two_contacts()
    rows, cols = np.nonzero(np.ones_like(W))
    values = W[rows, cols]
    # Each entry given as two halves: duplicates are summed, as scipy's COO does.
    p = coulomb.ContactProblem((np.r_[rows, rows], np.r_[cols, cols], np.r_[values, values] / 2),
                               q, mu)
    assert p.storage == "block_sparse"
    np.testing.assert_allclose(p.W, W, rtol=0, atol=1e-15)
    r, c, v = p.W_triplets()
    back = np.zeros_like(W)
    back[r, c] = v
    np.testing.assert_array_equal(back, p.W)


def test_scipy_sparse_matrix_is_accepted():
    sparse = pytest.importorskip("scipy.sparse")
    W, q, mu = two_contacts()
    p = coulomb.ContactProblem(sparse.csr_matrix(W), q, mu)
    assert p.storage == "block_sparse"
    np.testing.assert_allclose(p.W, W, rtol=0, atol=1e-15)


class CooLike:
    """What coulomb reads of a scipy.sparse matrix: tocoo() with row, col, data and shape."""

    def __init__(self, W):
        self.row, self.col = np.nonzero(W)
        self.data, self.shape = W[self.row, self.col], W.shape

    def tocoo(self):
        return self


def test_any_matrix_with_tocoo_is_accepted_without_scipy():
    W, q, mu = two_contacts()
    p = coulomb.ContactProblem(CooLike(W), q, mu)
    np.testing.assert_array_equal(p.W, W)
    with pytest.raises(ValueError, match=r"W: expected shape \(6, 6\) to match q, got \(3, 3\)"):
        coulomb.ContactProblem(CooLike(np.eye(3)), q, mu)


def test_zero_off_diagonal_blocks_are_not_stored():
    W = np.eye(6)
    p = coulomb.ContactProblem((np.arange(6), np.arange(6), np.ones(6)), -np.ones(6), [0.1, 0.2])
    r, c, _ = p.W_triplets()
    assert set(zip(r // 3, c // 3)) == {(0, 0), (1, 1)}
    np.testing.assert_array_equal(p.W, W)


def test_mixed_blocks():
    W = np.diag([2.0, 3.0, 1.0, 1.0, 1.0, 4.0])
    blocks = [coulomb.Block.equality(), coulomb.Block.bounded(-1.0, 2.0),
              coulomb.Block.contact(0.4), coulomb.Block.unilateral()]
    p = coulomb.ContactProblem(W, np.zeros(6), blocks=blocks)
    assert [b.kind for b in p.blocks] == ["equality", "bounded", "contact", "unilateral"]
    assert [b.size for b in p.blocks] == [1, 1, 3, 1]
    assert p.blocks[1].lower == -1.0 and p.blocks[1].upper == 2.0
    np.testing.assert_array_equal(p.mu, [0.4])
    aniso = coulomb.Block.anisotropic(0.2, 0.6)
    assert aniso.is_anisotropic and aniso.mu1 == 0.2 and aniso.mu2 == 0.6 and aniso.mu == 0.6
    assert repr(aniso) == "Block.anisotropic(0.20000000000000001, 0.59999999999999998)"


def test_warm_start_round_trip():
    W, q, mu = two_contacts()
    p = coulomb.ContactProblem(W, q, mu, warm_start=np.arange(6.0))
    np.testing.assert_array_equal(p.warm_start, np.arange(6.0))
    p.warm_start = None
    assert p.warm_start is None
    with pytest.raises(ValueError, match=r"warm_start: expected shape \(6,\)"):
        p.warm_start = np.zeros(5)


@pytest.mark.parametrize("dense", [True, False])
def test_pickle_keeps_everything_and_solves_bit_identically(dense):
    W, q, mu = two_contacts()
    given = W if dense else tuple(np.nonzero(np.ones_like(W))) + (W.ravel(),)
    p = coulomb.ContactProblem(given, q, mu, name="pickled", warm_start=np.full(6, 0.1))
    back = pickle.loads(pickle.dumps(p))
    assert back.name == "pickled" and back.storage == p.storage
    np.testing.assert_array_equal(back.W, p.W)
    np.testing.assert_array_equal(back.warm_start, p.warm_start)
    a, b = coulomb.solve(p, "ac_newton"), coulomb.solve(back, "ac_newton")
    np.testing.assert_array_equal(a.impulses, b.impulses)
    assert a.residual == b.residual and a.iterations == b.iterations
    assert pickle.loads(pickle.dumps(coulomb.Block.bounded(-1, 1))) == coulomb.Block.bounded(-1, 1)


def test_fc3d_round_trip_is_exact(fc3d_files, tmp_path):
    assert fc3d_files, "tests/data/fc3d has the Siconos fixtures"
    for path in fc3d_files:
        p = coulomb.read_fc3d(str(path))
        again = coulomb.parse_fc3d(p.to_fc3d(), source=path.name)
        np.testing.assert_array_equal(again.W, p.W)
        np.testing.assert_array_equal(again.q, p.q)
        np.testing.assert_array_equal(again.mu, p.mu)
        assert again.name == p.name
        out = tmp_path / path.name
        coulomb.write_fc3d(p, str(out), family="test")
        assert out.read_text().startswith("# family: test\n")
        np.testing.assert_array_equal(coulomb.read_fc3d(str(out)).W, p.W)
