#!/usr/bin/env node
// Writes a deterministic random serial chain of N revolute joints as URDF.
//
//   node robots/generate_chain.mjs N [--seed S] > out.urdf
//   node robots/generate_chain.mjs N [--seed S] --q0     (prints a default q0 as JSON)
//
// The seed may also be given as a second positional argument (N S); the
// header comment of the output uses that form because XML forbids "--"
// inside comments. The seed defaults to 1.
//
// Links link0 (root, massless fixed base) .. linkN (tip), joints joint1..jointN.
// The same N and S always give the same bytes: the only randomness is a
// mulberry32 generator, and the output uses no trigonometry (directions come
// from normalised vectors, rotations from orthonormal frames), so the numbers
// do not depend on the platform's libm.
//
// Each joint i:
//   origin xyz  a vector of length 0.1-0.3 m in the parent link frame, leaning
//               towards +z (joint1 sits 0.1 m above the base);
//   origin rpy  each angle uniform in [-0.8, 0.8] rad;
//   axis        +-x, +-y or +-z, never parallel to the previous joint's axis;
//   limits      [-pi, pi], effort 10000 N m, velocity 10 rad/s;
//   dynamics    damping 0.1 N m s/rad, friction 0.
// Each link i >= 1 is a solid box of mass 0.5-2 kg, 0.03-0.08 m wide and deep,
// whose long side runs from the link's origin to the next joint's origin (for
// the tip, to a virtual next joint); its centre of mass is halfway along, and
// its tensor is the box's principal tensor rotated into the link frame, so the
// off-diagonal terms are nonzero and the triangle inequality holds.

const USAGE = 'usage: node robots/generate_chain.mjs N [S | --seed S] [--q0]';

function fail(message) {
  process.stderr.write(`generate_chain: ${message}\n${USAGE}\n`);
  process.exit(2);
}

function parseArgs(argv) {
  let n = null;
  let seed = null;
  let q0 = false;
  for (let i = 0; i < argv.length; i++) {
    const arg = argv[i];
    if (arg === '--seed') {
      const value = argv[++i];
      if (value === undefined || !/^\d+$/.test(value)) fail('--seed needs a non-negative integer');
      if (seed !== null) fail('the seed is given twice');
      seed = Number(value);
    } else if (arg === '--q0') {
      q0 = true;
    } else if (arg === '-h' || arg === '--help') {
      process.stdout.write(`${USAGE}\n`);
      process.exit(0);
    } else if (n === null && /^\d+$/.test(arg)) {
      n = Number(arg);
    } else if (seed === null && /^\d+$/.test(arg)) {
      seed = Number(arg);
    } else {
      fail(`unexpected argument '${arg}'`);
    }
  }
  if (n === null || n < 1) fail('N must be a positive integer');
  if (seed === null) seed = 1;
  if (seed > 0xffffffff) fail('the seed must fit in 32 bits');
  return { n, seed, q0 };
}

// mulberry32: a small 32-bit PRNG, uniform in [0, 1).
function mulberry32(seed) {
  let a = seed >>> 0;
  return function next() {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

const uniform = (rand, lo, hi) => lo + (hi - lo) * rand();
// Values are rounded before use, so the printed file is exactly what the
// inertias were computed from.
const round6 = (x) => Number(x.toFixed(6));
const round4 = (x) => Number(x.toFixed(4));
const norm = (v) => Math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
const scale = (v, s) => [v[0] * s, v[1] * s, v[2] * s];
const cross = (a, b) => [
  a[1] * b[2] - a[2] * b[1],
  a[2] * b[0] - a[0] * b[2],
  a[0] * b[1] - a[1] * b[0],
];

// Fixed-point text, so the file is stable and short ("-0.000000" becomes "0").
function num(x, digits = 6) {
  const s = x.toFixed(digits).replace(/\.?0+$/, '');
  return s === '-0' ? '0' : s;
}

// Significant-digit text for inertia entries (they span several decades).
function sig(x) {
  const s = Number(x.toPrecision(9)).toString();
  return s === '-0' ? '0' : s;
}

// A segment vector of length 0.1-0.3 m in the parent frame, leaning towards +z.
function randomOffset(rand) {
  const d = [uniform(rand, -0.6, 0.6), uniform(rand, -0.6, 0.6), uniform(rand, 0.3, 1.0)];
  const length = uniform(rand, 0.1, 0.3);
  return scale(d, length / norm(d)).map(round6);
}

const AXES = [
  [1, 0, 0], [-1, 0, 0],
  [0, 1, 0], [0, -1, 0],
  [0, 0, 1], [0, 0, -1],
];

// Box inertia about its centre, turned so the box's long side is along `along`:
// I = R diag(Ia, Ib, Ic) R^T with R = [e1 e2 e3], e3 = along / |along|.
function boxInertia(mass, width, depth, along) {
  const length = norm(along);
  const e3 = scale(along, 1 / length);
  const helper = Math.abs(e3[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0];
  const c = cross(helper, e3);
  const e1 = scale(c, 1 / norm(c));
  const e2 = cross(e3, e1);
  const principal = [
    (mass * (depth * depth + length * length)) / 12, // about e1 (width direction)
    (mass * (width * width + length * length)) / 12, // about e2 (depth direction)
    (mass * (width * width + depth * depth)) / 12, //   about e3 (long side)
  ];
  const axes = [e1, e2, e3];
  const I = [[0, 0, 0], [0, 0, 0], [0, 0, 0]];
  for (let r = 0; r < 3; r++) {
    for (let s = 0; s < 3; s++) {
      for (let k = 0; k < 3; k++) I[r][s] += axes[k][r] * principal[k] * axes[k][s];
    }
  }
  return I;
}

function buildChain(n, seed) {
  const rand = mulberry32(seed);
  const joints = [];
  let previousAxis = -1;
  for (let i = 1; i <= n; i++) {
    const xyz = i === 1 ? [0, 0, 0.1] : randomOffset(rand);
    const rpy = [uniform(rand, -0.8, 0.8), uniform(rand, -0.8, 0.8), uniform(rand, -0.8, 0.8)].map(round6);
    let axis;
    do {
      axis = Math.floor(rand() * AXES.length);
    } while (previousAxis >= 0 && Math.floor(axis / 2) === Math.floor(previousAxis / 2));
    previousAxis = axis;
    joints.push({ xyz, rpy, axis: AXES[axis] });
  }
  // Link i spans from its origin to joint i+1's origin; the tip gets a virtual one.
  const links = [];
  for (let i = 1; i <= n; i++) {
    const along = i < n ? joints[i].xyz : randomOffset(rand);
    const mass = round4(uniform(rand, 0.5, 2.0));
    const width = round4(uniform(rand, 0.03, 0.08));
    const depth = round4(uniform(rand, 0.03, 0.08));
    links.push({ mass, com: scale(along, 0.5), inertia: boxInertia(mass, width, depth, along) });
  }
  return { joints, links };
}

function toUrdf(n, seed, chain) {
  const out = [];
  out.push('<?xml version="1.0"?>');
  out.push('<!--');
  out.push(`  Generated by: node robots/generate_chain.mjs ${n} ${seed} > robots/chain${n}.urdf`);
  out.push(`  (N = ${n} links, seed = ${seed}).`);
  out.push('  Do not edit by hand; change the generator and regenerate.');
  out.push(`  A random serial chain of ${n} revolute joints: link0 (root, massless fixed`);
  out.push(`  base) .. link${n} (tip), joints joint1..joint${n}. See robots/README.md.`);
  out.push('-->');
  out.push(`<robot name="chain${n}">`);
  out.push('  <link name="link0"/>');
  for (let i = 1; i <= n; i++) {
    const j = chain.joints[i - 1];
    const l = chain.links[i - 1];
    const I = l.inertia;
    out.push('');
    out.push(`  <joint name="joint${i}" type="revolute">`);
    out.push(`    <parent link="link${i - 1}"/>`);
    out.push(`    <child link="link${i}"/>`);
    out.push(`    <origin xyz="${j.xyz.map((v) => num(v)).join(' ')}" rpy="${j.rpy.map((v) => num(v)).join(' ')}"/>`);
    out.push(`    <axis xyz="${j.axis.join(' ')}"/>`);
    out.push('    <limit lower="-3.141592653589793" upper="3.141592653589793" effort="10000" velocity="10"/>');
    out.push('    <dynamics damping="0.1" friction="0"/>');
    out.push('  </joint>');
    out.push(`  <link name="link${i}">`);
    out.push('    <inertial>');
    out.push(`      <origin xyz="${l.com.map((v) => num(v, 7)).join(' ')}" rpy="0 0 0"/>`);
    out.push(`      <mass value="${num(l.mass, 4)}"/>`);
    out.push(
      `      <inertia ixx="${sig(I[0][0])}" ixy="${sig(I[0][1])}" ixz="${sig(I[0][2])}"` +
        ` iyy="${sig(I[1][1])}" iyz="${sig(I[1][2])}" izz="${sig(I[2][2])}"/>`,
    );
    out.push('    </inertial>');
    out.push('  </link>');
  }
  out.push('</robot>');
  return out.join('\n') + '\n';
}

// A default pose for robots/index.json: each angle uniform in [-0.6, 0.6] rad,
// from its own stream so that it does not change the chain.
function defaultPose(n, seed) {
  const rand = mulberry32((seed ^ 0x9e3779b9) >>> 0);
  const q = [];
  for (let i = 0; i < n; i++) q.push(Number(uniform(rand, -0.6, 0.6).toFixed(3)));
  return q;
}

const { n, seed, q0 } = parseArgs(process.argv.slice(2));
if (q0) {
  process.stdout.write(JSON.stringify(defaultPose(n, seed)) + '\n');
} else {
  process.stdout.write(toUrdf(n, seed, buildChain(n, seed)));
}
