"""The solver kernel alone: Cholesky and UpdatableCholesky on scipy.sparse matrices."""

import numpy as np
import pytest
import scipy.sparse
import scipy.sparse.linalg

import lapis


def spd(n=200, seed=1):
    """A sparse SPD matrix: a mesh Laplacian's stiffness plus mass."""
    V, F = lapis.make_icosphere(2)
    K = -lapis.cotan_laplacian(V, F) + lapis.mass_matrix(V, F)
    return K.tocsc()


def test_cholesky_matches_scipy():
    A = spd()
    rng = np.random.default_rng(1)
    B = rng.standard_normal((A.shape[0], 3))
    chol = lapis.Cholesky()
    chol.compute(A)
    X = chol.solve(B)
    assert X.shape == B.shape
    assert np.allclose(X, scipy.sparse.linalg.spsolve(A, B), rtol=1e-10, atol=1e-12)
    x = chol.solve(B[:, 0])  # a vector in, a vector out
    assert x.shape == (A.shape[0],) and np.array_equal(x, X[:, 0])
    assert chol.report()["n"] == A.shape[0] and chol.factorized
    # Only the lower triangle is read, as in C++.
    chol.compute(scipy.sparse.tril(A))
    assert np.allclose(chol.solve(B), X, rtol=1e-12, atol=1e-14)
    assert np.allclose(lapis.solve_spd(A, B), X, rtol=1e-12, atol=1e-14)


def test_cholmod_and_eigen_backends_agree():
    A = spd()
    b = np.linspace(0, 1, A.shape[0])
    x = {}
    for backend in ("cholmod", "eigen"):
        c = lapis.Cholesky(backend=backend)
        c.compute(A)
        x[backend] = c.solve(b)
    assert np.allclose(x["cholmod"], x["eigen"], rtol=1e-10, atol=1e-12)


def test_not_positive_definite_names_the_column():
    A = spd().tolil()
    A[7, 7] = -1.0
    with pytest.raises(lapis.NotPositiveDefinite) as e:
        lapis.Cholesky().compute(A.tocsc())
    assert isinstance(e.value, ArithmeticError) and isinstance(e.value, lapis.Error)
    assert e.value.column >= 0 and "not positive definite" in str(e.value)


def test_update_downdate_match_refactorization():
    A = spd()
    n = A.shape[0]
    C = scipy.sparse.random(n, 2, density=0.05, random_state=3, format="csc")
    b = np.ones(n)
    f = lapis.UpdatableCholesky(method="update/downdate")
    f.compute(A)
    r = f.update(C)
    assert r["method"] == "update/downdate" and r["rank"] == 2
    assert np.allclose(f.solve(b), scipy.sparse.linalg.spsolve((A + C @ C.T).tocsc(), b), rtol=1e-9)
    f.downdate(C)
    assert np.allclose(f.solve(b), scipy.sparse.linalg.spsolve(A, b), rtol=1e-9)
    assert abs(f.matrix() - A).max() < 1e-12


def test_diagonal_weights():
    A = spd()
    n = A.shape[0]
    w = np.zeros(n)
    w[:5] = 10.0
    f = lapis.UpdatableCholesky()
    f.compute(A, w)
    assert f.diagonal_weight(0) == 10.0
    f.set_diagonal_weights([0, 1, 50], [0.0, 20.0, 5.0])
    w[[0, 1, 50]] = [0.0, 20.0, 5.0]
    b = np.arange(n, dtype=float)
    assert np.allclose(f.solve(b), scipy.sparse.linalg.spsolve((A + scipy.sparse.diags(w)).tocsc(), b), rtol=1e-9)
    assert f.last_report()["method"] in ("update/downdate", "refactorize")
    with pytest.raises(ValueError, match="indices has 2 entries but weights has 1"):
        f.set_diagonal_weights([0, 1], [1.0])


def test_sparse_arguments_are_checked():
    with pytest.raises(TypeError, match="A must be a scipy.sparse matrix"):
        lapis.Cholesky().compute(np.eye(3))
    with pytest.raises(TypeError, match="A.data must be float64, not int64"):
        lapis.Cholesky().compute(scipy.sparse.identity(3, dtype=np.int64, format="csc"))
    c = lapis.Cholesky()
    c.compute(scipy.sparse.identity(3, format="csc"))
    with pytest.raises(lapis.InvalidArgument, match="Cholesky::solve"):
        c.solve(np.ones(4))
