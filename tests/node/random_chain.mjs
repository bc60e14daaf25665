// Seeded random serial chains as URDF text and random cases for them, for the parity
// tests: mixed revolute, continuous, prismatic and fixed joints, arbitrary unit axes,
// full (rotated) inertia tensors, and a fixed tool link at the tip half of the time.
//
// Rotations are written without rpy on purpose. urdfdom turns an rpy into a quaternion
// with the platform's sin and cos, and glibc (native) and musl (wasm) differ in the last
// bit of some of those; the solver amplifies a 1-ulp change of the model by up to the
// coupling matrix's condition number (1e4 here), which is the size of the 1e-12 bound.
// So frames differ by the joints' own motion (arbitrary axes) and inertias are rotated
// here, exactly the same numbers on both sides; rpy origins are covered by the robots
// of robots/ in these tests and by the native suites' random chains.

// xorshift32 scaled to [0, 1): deterministic for a seed, platform independent. The seed
// is scrambled first (multiply by the golden ratio, xor-shift) so that neighbouring
// seeds do not start with neighbouring draws.
export function rng(seed) {
  let s = Math.imul((seed >>> 0) ^ 0x5bd1e995, 0x9e3779b9) >>> 0;
  s = (s ^ (s >>> 16)) >>> 0 || 0x9e3779b9;
  return () => {
    s ^= s << 13; s >>>= 0;
    s ^= s >>> 17;
    s ^= s << 5; s >>>= 0;
    return s / 4294967296;
  };
}

const uniform = (r, lo, hi) => lo + (hi - lo) * r();
const pick = (r, items) => items[Math.floor(r() * items.length)];
const vec = (r, lo, hi, n) => Array.from({ length: n }, () => uniform(r, lo, hi));
const unit = (v) => { const n = Math.hypot(...v); return v.map((x) => x / n); };
const xyz = (v) => v.join(' ');

// Principal moments of a solid box of mass m and sides a, b, c (triangle inequality holds).
function boxInertia(m, [a, b, c]) {
  return [m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12];
}

// R diag(d) R^T for the rotation of a random unit quaternion (no trigonometry).
function rotatedInertia(r, d) {
  const [w, x, y, z] = unit(vec(r, -1, 1, 4));
  const R = [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
             [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
             [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]];
  const I = (i, j) => R[i][0] * d[0] * R[j][0] + R[i][1] * d[1] * R[j][1] + R[i][2] * d[2] * R[j][2];
  return { ixx: I(0, 0), ixy: I(0, 1), ixz: I(0, 2), iyy: I(1, 1), iyz: I(1, 2), izz: I(2, 2) };
}

function link(r, name) {
  const m = uniform(r, 0.2, 3);
  const I = rotatedInertia(r, boxInertia(m, vec(r, 0.03, 0.4, 3)));
  return `  <link name="${name}">
    <inertial>
      <origin xyz="${xyz(vec(r, -0.1, 0.1, 3))}"/>
      <mass value="${m}"/>
      <inertia ixx="${I.ixx}" ixy="${I.ixy}" ixz="${I.ixz}" iyy="${I.iyy}" iyz="${I.iyz}" izz="${I.izz}"/>
    </inertial>
  </link>
`;
}

// A chain of `movable` joints (plus some fixed ones) between links base .. tip.
export function randomChain(seed, movable) {
  const r = rng(seed);
  const names = ['base'];
  let xml = `<?xml version="1.0"?>\n<robot name="random_${seed}">\n  <link name="base"/>\n`;
  let moved = 0, k = 0;
  while (moved < movable) {
    const fixed = k > 0 && r() < 0.15;
    const type = fixed ? 'fixed' : pick(r, ['revolute', 'revolute', 'continuous', 'prismatic']);
    const child = `link${++k}`;
    xml += link(r, child);
    xml += `  <joint name="joint${k}" type="${type}">
    <parent link="${names[names.length - 1]}"/>
    <child link="${child}"/>
    <origin xyz="${xyz(vec(r, -0.3, 0.3, 3))}"/>
`;
    if (!fixed) xml += `    <axis xyz="${xyz(unit(vec(r, -1, 1, 3)))}"/>
    <dynamics damping="${uniform(r, 0, 0.5)}" friction="0"/>
`;
    if (type === 'revolute' || type === 'prismatic')
      xml += `    <limit lower="-3" upper="3" effort="100" velocity="5"/>\n`;
    xml += '  </joint>\n';
    names.push(child);
    if (!fixed) ++moved;
  }
  if (r() < 0.5) {
    xml += link(r, 'tool');
    xml += `  <joint name="tool_joint" type="fixed">
    <parent link="${names[names.length - 1]}"/>
    <child link="tool"/>
    <origin xyz="${xyz(vec(r, -0.1, 0.1, 3))}"/>
  </joint>
`;
    names.push('tool');
  }
  return { text: `${xml}</robot>\n`, root: 'base', tip: names[names.length - 1] };
}

// A case for a robot with nj joints and nl links after the root, nc constraints.
export function randomCase(r, nj, nl, nc) {
  const c = {
    q: vec(r, -3, 3, nj),
    qd: vec(r, -2, 2, nj),
    gravity: r() < 0.5 ? [0, 0, -9.81] : vec(r, -10, 10, 3),
    ff_torques: vec(r, -5, 5, nj),
  };
  if (nc > 0) {
    c.alpha = Array.from({ length: nc }, () => vec(r, -1, 1, 6));
    c.beta = vec(r, -1, 1, nc);
  }
  if (r() < 0.5) c.f_ext = Array.from({ length: nl }, () => vec(r, -3, 3, 6));
  return c;
}
