// The pose a robot without a listed start pose (an own URDF) starts from: inside its
// joint limits and away from a singularity of the tip Jacobian. The plain choice (0, or
// the middle of the limits when 0 is outside them) is often singular: the middle of
// symmetric limits is the stretched pose (the KUKA LWR 4 at q = 0 stands straight up and
// loses three tip directions), where a held or accelerated direction cannot be followed.
//
// A pose is scored by the smallest singular value of the tip Jacobian relative to the
// largest, for the whole Jacobian and for its linear and angular rows apart (linear rows
// are in m/rad, angular ones unitless; a stretched planar arm is singular only in the
// linear rows). The smallest value is counted at the chain's generic rank (the largest
// rank over the poses tried), since a chain that cannot move the tip in six directions
// has zero singular values everywhere. The plain pose is kept when its score is at least
// MIN_SCORE; otherwise poses around it, spread ever wider, are tried in a fixed
// pseudo-random order, and the first one that reaches MIN_SCORE (or the best) is taken.
import { singularValues } from './singular_values.js';

// Poses the robots of robots/index.json start from score 0.097 (LWR, UR5) and more.
export const MIN_SCORE = 0.05;
// Singular values below this fraction of the largest count as zero when finding the rank.
const RANK_TOLERANCE = 1e-9;
// Start poses keep this fraction of a joint's range away from each of its limits.
const LIMIT_MARGIN = 0.05;
const SPREADS = [0.25, 0.5, 1];
const TRIES_PER_SPREAD = 16;
// How far an unlimited joint is moved at spread 1, in rad or m.
const UNLIMITED_REACH = { revolute: Math.PI / 2, continuous: Math.PI / 2, prismatic: 0.1 };
const SEED = 0x2545f491;

const BLOCKS = [[0, 6], [0, 3], [3, 6]];

// robot: an achd robot (limits, jointTypes, tipJacobian). Returns {q, score}.
export function startPose(robot) {
  const ranges = robot.limits.map((l, j) => jointRange(l, robot.jointTypes[j]));
  const plain = ranges.map((r) => r.plain);
  const candidates = [plain];
  const random = mulberry32(SEED);
  for (const spread of SPREADS) {
    for (let k = 0; k < TRIES_PER_SPREAD; k++) {
      candidates.push(ranges.map((r) => clamp(r.plain + spread * (2 * random() - 1) * r.reach, r.low, r.high)));
    }
  }
  const spectra = candidates.map((q) => {
    const J = robot.tipJacobian(q);
    return BLOCKS.map(([from, to]) => singularValues(J.slice(from, to)));
  });
  const ranks = BLOCKS.map((_, b) => Math.max(...spectra.map((s) => rank(s[b]))));
  const scores = spectra.map((s) => Math.min(...s.map((values, b) => (ranks[b] ? values[ranks[b] - 1] / values[0] : 1))));
  let best = 0;
  for (let i = 0; i < candidates.length; i++) {
    if (scores[i] >= MIN_SCORE) return { q: candidates[i], score: scores[i] };
    if (scores[i] > scores[best]) best = i;
  }
  return { q: candidates[best], score: scores[best] };
}

// The plain start value of a joint and the interval start poses keep to.
function jointRange(limit, type) {
  const bounded = Number.isFinite(limit.lower) && Number.isFinite(limit.upper);
  if (!bounded) {
    const reach = UNLIMITED_REACH[type] ?? UNLIMITED_REACH.revolute;
    return { plain: 0, reach, low: -Infinity, high: Infinity };
  }
  const margin = LIMIT_MARGIN * (limit.upper - limit.lower);
  const low = limit.lower + margin;
  const high = limit.upper - margin;
  const plain = low <= 0 && 0 <= high ? 0 : (limit.lower + limit.upper) / 2;
  return { plain, reach: (limit.upper - limit.lower) / 2, low, high };
}

function rank(values) {
  return values.filter((s) => s > RANK_TOLERANCE * values[0]).length;
}

function clamp(x, low, high) {
  return Math.min(Math.max(x, low), high);
}

// A small seeded generator (Tommy Ettinger's mulberry32): the same URDF always gets the
// same start pose.
function mulberry32(seed) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}
