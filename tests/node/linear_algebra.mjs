// Small dense linear algebra for the tests: the constraint coupling matrix of a case
// and its condition number, computed independently of the solver.

// Eigenvalues of a symmetric matrix (array of rows) by cyclic Jacobi rotations.
export function symmetricEigenvalues(A) {
  const n = A.length, a = A.map((row) => row.slice());
  for (let sweep = 0; sweep < 100; ++sweep) {
    let off = 0;
    for (let p = 0; p < n; ++p) for (let q = p + 1; q < n; ++q) off += a[p][q] * a[p][q];
    if (off < 1e-300) break;
    for (let p = 0; p < n; ++p) {
      for (let q = p + 1; q < n; ++q) {
        if (a[p][q] === 0) continue;
        // Rotation angle that zeroes a[p][q]: tan(2 theta) = 2 a_pq / (a_qq - a_pp).
        const theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
        const t = Math.sign(theta || 1) / (Math.abs(theta) + Math.sqrt(theta * theta + 1));
        const c = 1 / Math.sqrt(t * t + 1), s = t * c;
        for (let k = 0; k < n; ++k) {
          const akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (let k = 0; k < n; ++k) {
          const apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
      }
    }
  }
  return a.map((row, i) => row[i]);
}

// Solves M X = B for symmetric positive definite M (Cholesky); B and X: arrays of rows.
export function choleskySolve(M, B) {
  const n = M.length, L = M.map(() => new Array(n).fill(0));
  for (let i = 0; i < n; ++i) {
    for (let j = 0; j <= i; ++j) {
      let s = M[i][j];
      for (let k = 0; k < j; ++k) s -= L[i][k] * L[j][k];
      L[i][j] = i === j ? Math.sqrt(s) : s / L[j][j];
    }
  }
  const m = B[0].length, X = B.map((row) => row.slice());
  for (let c = 0; c < m; ++c) {
    for (let i = 0; i < n; ++i) {  // L y = b
      let s = X[i][c];
      for (let k = 0; k < i; ++k) s -= L[i][k] * X[k][c];
      X[i][c] = s / L[i][i];
    }
    for (let i = n - 1; i >= 0; --i) {  // L^T x = y
      let s = X[i][c];
      for (let k = i + 1; k < n; ++k) s -= L[k][i] * X[k][c];
      X[i][c] = s / L[i][i];
    }
  }
  return X;
}

// K = A^T J M^-1 J^T A with A = alpha columns: how unit constraint forces at the tip
// accelerate the tip along the constraint directions (the solver's coupling matrix).
export function couplingMatrix(robot, q, alpha) {
  const J = robot.tipJacobian(q), M = robot.massMatrix(q);
  const nj = robot.numRates, nc = alpha.length;
  // JtA (nj x nc) = J^T alpha
  const JtA = Array.from({ length: nj }, (_, i) =>
    alpha.map((col) => col.reduce((s, x, r) => s + J[r][i] * x, 0)));
  const X = choleskySolve(M, JtA);
  return Array.from({ length: nc }, (_, a) => Array.from({ length: nc }, (_, b) => {
    let s = 0;
    for (let i = 0; i < nj; ++i) s += JtA[i][a] * X[i][b];
    return s;
  }));
}

export function conditionNumber(K) {
  const ev = symmetricEigenvalues(K).map(Math.abs);
  return { cond: Math.max(...ev) / Math.min(...ev), min: Math.min(...ev), max: Math.max(...ev) };
}
