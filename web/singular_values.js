// Singular values of a small dense matrix (a tip Jacobian, 6 rows by n columns), largest
// first: the square roots of the eigenvalues of the smaller Gram matrix (J J^T when n >= 6,
// J^T J otherwise), found by cyclic Jacobi rotations. Enough for the page's start pose,
// which only needs to tell a singular pose from a well-conditioned one; the solver's own
// sigma_min (achd) is the exact one.

const SWEEPS = 50;

// rows: an array of equal-length arrays of finite numbers.
export function singularValues(rows) {
  const m = rows.length;
  const n = m ? rows[0].length : 0;
  const wide = n >= m;
  const k = wide ? m : n;
  const gram = Array.from({ length: k }, () => new Array(k).fill(0));
  for (let i = 0; i < k; i++) {
    for (let j = i; j < k; j++) {
      let sum = 0;
      if (wide) for (let c = 0; c < n; c++) sum += rows[i][c] * rows[j][c];
      else for (let r = 0; r < m; r++) sum += rows[r][i] * rows[r][j];
      gram[i][j] = sum;
      gram[j][i] = sum;
    }
  }
  return symmetricEigenvalues(gram).map((e) => Math.sqrt(Math.max(e, 0))).sort((a, b) => b - a);
}

// Eigenvalues of a symmetric matrix (modified in place) by cyclic Jacobi rotations.
function symmetricEigenvalues(a) {
  const k = a.length;
  for (let sweep = 0; sweep < SWEEPS; sweep++) {
    let off = 0;
    let scale = 0;
    for (let i = 0; i < k; i++) {
      scale += a[i][i] * a[i][i];
      for (let j = i + 1; j < k; j++) off += a[i][j] * a[i][j];
    }
    if (off <= 1e-30 * scale || off === 0) break;
    for (let p = 0; p < k; p++) {
      for (let q = p + 1; q < k; q++) {
        if (a[p][q] === 0) continue;
        // The rotation that zeroes a[p][q] (Golub and Van Loan, algorithm 8.4.1).
        const theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
        const t = Math.sign(theta || 1) / (Math.abs(theta) + Math.sqrt(theta * theta + 1));
        const c = 1 / Math.sqrt(t * t + 1);
        const s = t * c;
        for (let r = 0; r < k; r++) {
          const arp = a[r][p];
          const arq = a[r][q];
          a[r][p] = c * arp - s * arq;
          a[r][q] = s * arp + c * arq;
        }
        for (let r = 0; r < k; r++) {
          const apr = a[p][r];
          const aqr = a[q][r];
          a[p][r] = c * apr - s * aqr;
          a[q][r] = s * apr + c * aqr;
        }
      }
    }
  }
  return a.map((row, i) => row[i]);
}
