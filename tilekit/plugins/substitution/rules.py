"""What every kind of substitution system shares: a rule (children and their maps) and the
substitution-matrix facts (matrix, Perron-Frobenius data, exact label counts)."""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass

import numpy as np


@dataclass
class Rule:
    """The substitution of one prototile: child prototile indices and their maps (m, 3, 3)."""

    children: np.ndarray
    matrices: np.ndarray


class MatrixFacts(ABC):
    """Substitution-matrix facts shared by every kind of system (similarity, keypoint, hat).

    A system provides ``n`` (number of labels), ``seed`` and ``child_labels()`` (per label,
    the labels of its children); the rest follows from the matrix.
    """

    n: int
    seed: int

    @abstractmethod
    def child_labels(self) -> list[np.ndarray]:
        """Per label j, the labels of the children in j's rule."""

    def substitution_matrix(self) -> np.ndarray:
        """M[i, j] = number of label-i children in the rule of label j."""
        m = np.zeros((self.n, self.n), dtype=np.int64)
        for j, kids in enumerate(self.child_labels()):
            np.add.at(m[:, j], kids, 1)
        return m

    def perron_frobenius(self) -> tuple[float, np.ndarray]:
        """The dominant eigenvalue of the substitution matrix and its eigenvector (sum 1).

        For a primitive matrix the normalised right eigenvector gives the limiting relative
        frequencies of the labels; for a self-similar system the eigenvalue is s**2.
        """
        m = self.substitution_matrix().astype(float)
        vals, vecs = np.linalg.eig(m)
        k = int(np.argmax(vals.real))
        vec = np.abs(vecs[:, k].real)
        return float(vals[k].real), vec / vec.sum()

    def leaf_tiles(self) -> np.ndarray:
        """Per label, the tiles a level-0 supertile of it is (1 each; monotile systems override)."""
        return np.ones(self.n)

    def descendants(self, n: int) -> np.ndarray:
        """Per label j, the tiles a level-n supertile of label j becomes: the row vector
        ``leaf_tiles() @ M^n`` (floats, so deep levels do not overflow)."""
        m = self.substitution_matrix().astype(float)
        v = np.asarray(self.leaf_tiles(), dtype=float)
        for _ in range(n):
            v = v @ m
        return v

    def counts(self, generations: int, start: int | None = None) -> list[list[int]]:
        """Label counts after 0..generations substitutions of one ``start`` tile (M^n e), exact."""
        mo = self.substitution_matrix().astype(object)
        v = np.zeros(self.n, dtype=object)
        v[self.seed if start is None else start] = 1
        out = [[int(x) for x in v]]
        for _ in range(generations):
            v = mo.dot(v)
            out.append([int(x) for x in v])
        return out
