// A property test of the JS boundary: random sequences of create, delete, view, write
// through views (live and stale), solve, step (with onProgress callbacks that delete,
// reset or re-configure their simulator, or create and delete others), reset and the
// direction setters, with inputs given as arrays, typed arrays, growing Proxies, getters
// and wrong kinds, for a bounded time: ACHD_FUZZ_SECONDS (default 3; CI may give 60).
// It asserts that nothing throws but a plain Error (never a RuntimeError of wasm, a
// TypeError or a RangeError), and that every solve and every undisturbed run gives the
// answer a fresh module gave for the same input before the sequence started.
// ACHD_FUZZ_SEED repeats a sequence (the seed is in every failure message).
import assert from 'node:assert/strict';
import { test } from 'node:test';

import { loadAchd, robots } from './helpers.mjs';

const SECONDS = Number(process.env.ACHD_FUZZ_SECONDS || 3);
const SEED = process.env.ACHD_FUZZ_SEED ? Number(process.env.ACHD_FUZZ_SEED) : (Date.now() % 2 ** 31);

// mulberry32: a small seeded generator, so that a failing sequence can be run again.
function generator(seed) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6D2B79F5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

test(`random create/delete/view/step/reset/setDirection sequences (${SECONDS} s, seed ${SEED})`, async () => {
  const achd = await loadAchd();
  const entry = robots().find((r) => r.name === 'kuka_lwr4');
  const rand = generator(SEED);
  const int = (n) => Math.floor(rand() * n);
  const pick = (list) => list[int(list.length)];
  const where = () => `seed ${SEED}, operation ${ops}`;
  const load = () => achd.loadURDF(entry.text, { root: entry.root, tip: entry.tip });

  // The answers of a fresh module, before any sequence: solves of a few cases and runs
  // of STEPS steps from their q.
  const STEPS = 30, n = 7;
  const cases = Array.from({ length: 4 }, (_, k) => ({
    q: entry.q0.map((x, i) => x + 0.1 * Math.sin(3 * k + i)), qd: Array.from({ length: n }, (_, i) => 0.2 * Math.cos(k + i)),
    gravity: [0.1 * k, 0, -9.81], alpha: k % 2 ? [[0, 0, 1, 0, 0, 0]] : [], beta: k % 2 ? [0.05] : [],
  }));
  const reference = load();
  const solved = cases.map((c) => reference.solve(c));
  const runs = cases.map((c) => {
    const sim = reference.createSimulator();
    sim.reset(c.q, c.qd);
    sim.step(STEPS);
    const q = Array.from(sim.q);
    sim.delete();
    return q;
  });
  reference.delete();

  // An input in one of the forms a caller may give: the plain array, a typed array, a
  // Proxy that claims to grow after its first read, an array with a getter (refused), a
  // Map or a string (refused).
  const forms = (values) => {
    switch (int(8)) {
      case 0: return Float64Array.from(values);
      case 1: {
        let reads = 0;
        return new Proxy(values.slice(), {
          get: (t, k, r) => (k === 'length' ? (++reads > 1 ? 4000 : t.length) : Reflect.get(t, k, r)),
          getOwnPropertyDescriptor: (t, k) => {
            const d = Reflect.getOwnPropertyDescriptor(t, k);
            return k === 'length' ? { ...d, value: ++reads > 1 ? 4000 : t.length } : d;
          },
        });
      }
      case 2: { const a = values.slice(); Object.defineProperty(a, 0, { get: () => values[0], enumerable: true }); return a; }
      case 3: return new Map(values.map((x, i) => [i, x]));
      case 4: return String(values);
      default: return values.slice();
    }
  };
  // Whether a form may be refused (and must be, with a plain Error).
  const refusable = (v) => !(Array.isArray(v) && Object.getOwnPropertyDescriptor(v, 0)?.get === undefined) && !(v instanceof Float64Array);

  const live = { robots: [], solvers: [], sims: [] };
  const views = [];  // [object, view] pairs, kept after delete()
  let ops = 0, checks = 0;

  // Runs fn; an exception must be a plain Error (a refusal or a deleted object).
  const guarded = (fn, what) => {
    try {
      return fn();
    } catch (e) {
      assert.equal(e?.constructor, Error, `${what} threw ${e?.constructor?.name}: ${e?.message} (${where()})`);
      return undefined;
    }
  };
  const remove = (list, x) => list.splice(list.indexOf(x), 1);
  const anyObject = () => pick([...live.robots, ...live.solvers, ...live.sims]);

  const operations = [
    () => { if (live.robots.length < 3) live.robots.push(load()); },
    () => {  // delete something (a robot's solvers and simulators stay usable without it)
      const o = anyObject();
      if (!o) return;
      o.delete();
      for (const list of Object.values(live)) if (list.includes(o)) remove(list, o);
    },
    () => { const r = pick(live.robots); if (r && live.solvers.length < 4) live.solvers.push(r.createSolver()); },
    () => { const r = pick(live.robots); if (r && live.sims.length < 4) live.sims.push(r.createSimulator()); },
    () => {  // take a view
      const o = pick([...live.solvers, ...live.sims]);
      if (o) views.push([o, o[pick(['q', 'qd', 'ff_torques', 'f_ext'])]]);
    },
    () => {  // write through a view of a deleted object: it must be zero-length
      const stale = views.filter(([o]) => o.deleted);
      if (!stale.length) return;
      const [, v] = pick(stale);
      assert.equal(v.length, 0, `a view of a deleted object has ${v.length} elements (${where()})`);
      v[int(8)] = 1e300;  // dropped
      assert.throws(() => v.fill(NaN), TypeError);  // a detached buffer: nothing written
    },
    () => {  // robot.solve of a case with one input in a random form
      const r = pick(live.robots);
      if (!r) return;
      const k = int(cases.length), field = pick(['q', 'qd', 'gravity']);
      const input = forms(cases[k][field]);
      const result = guarded(() => r.solve({ ...cases[k], [field]: input }), `solve(${field})`);
      if (result !== undefined) {
        assert.deepEqual(result, solved[k], `solve of case ${k} with ${field} as given (${where()})`);
        ++checks;
      } else {
        assert.ok(refusable(input), `a plain ${field} was refused (${where()})`);
      }
    },
    () => {  // the zero-copy solver through its views (read again after anything)
      const s = pick(live.solvers);
      if (!s) return;
      const k = int(cases.length), c = cases[k];
      s.q.set(c.q);
      s.qd.set(c.qd);
      s.ff_torques.fill(0);
      s.gravity.set(c.gravity);
      s.numConstraints = c.alpha.length;
      c.alpha.forEach((col, j) => s.alpha.set(col, 6 * j));
      s.beta.set(c.beta);
      s.w_fext.fill(1, 0, c.alpha.length);
      s.w_ff.fill(1, 0, c.alpha.length);
      s.setConstraints([]);
      s.setPrescribed([]);
      s.useExternalWrenches = false;
      s.useVirtualWrenches = false;
      s.solve();
      assert.deepEqual(Array.from(s.qdd), solved[k].qdd, `zero-copy solve of case ${k} (${where()})`);
      ++checks;
    },
    () => {  // a run with onProgress doing something random to this or other objects
      const sim = pick(live.sims);
      if (!sim) return;
      const k = int(cases.length);
      const q0 = forms(cases[k].q);
      if (guarded(() => { sim.reset(q0, cases[k].qd); return true; }, 'reset') !== true) {
        assert.ok(refusable(q0), `reset refused a q it takes (${where()})`);
        return;  // refused: not a clean start
      }
      const action = int(6);
      let disturbed = false;
      const onProgress = () => {
        switch (action) {
          case 0: sim.delete(); remove(live.sims, sim); disturbed = 'deleted'; break;
          case 1: sim.reset(cases[k].q, cases[k].qd); disturbed = 'reset'; break;
          case 2: { const o = pick(live.sims.filter((x) => x !== sim)); if (o) { o.delete(); remove(live.sims, o); } break; }
          case 3: { const r = load(); const s = r.createSimulator(); const v = s.q; s.delete(); v[1] = 1; r.delete(); break; }
          case 4: guarded(() => sim.step(1), 'nested step'); break;
          default: break;
        }
      };
      const interval = 1 + int(STEPS);
      try {
        assert.equal(sim.step(STEPS, 1e-3, { progressInterval: interval, onProgress }), STEPS);
        assert.equal(disturbed, false, `step() went on after its callback ${disturbed} the simulator (${where()})`);
        assert.deepEqual(Array.from(sim.q), runs[k], `an undisturbed run from case ${k} (${where()})`);
        ++checks;
      } catch (e) {
        if (e instanceof assert.AssertionError) throw e;
        assert.equal(e.constructor, Error, `step threw ${e.constructor.name}: ${e.message} (${where()})`);
        if (action === 4) assert.match(e.message, /called from its own onProgress callback/);
        else assert.match(e.message, new RegExp(`the onProgress callback ${disturbed} the simulator`), `${e.message} (${where()})`);
      }
    },
    () => {  // the direction setters with good and bad arguments
      const sim = pick(live.sims);
      if (!sim) return;
      const name = pick(['x', 'y', 'z', 'rx', 'w', null]);
      guarded(() => sim.setDirection(name, pick(['hold', 'free', 0.5, NaN, '1', undefined])), 'setDirection');
      guarded(() => sim.setDirectionWeights(name, pick([undefined, null, { wFext: 0.5 }, { wFf: '0.5' }, new Map(),
        { wFext: 2 }])), 'setDirectionWeights');
      guarded(() => sim.setDirectionPoint(entry.tip, forms([0, 0, 0.01 * int(5)])), 'setDirectionPoint');
    },
    () => {  // use of a deleted object: a plain Error
      const stale = views.filter(([o]) => o.deleted);
      if (!stale.length) return;
      const [o] = pick(stale);
      assert.throws(() => o.q, /has been deleted/);
    },
  ];

  const end = Date.now() + 1000 * SECONDS;
  while (Date.now() < end) {
    ++ops;
    pick(operations)();
    if (views.length > 200) views.splice(0, 100);
  }
  for (const list of Object.values(live)) for (const o of list) o.delete();
  // And a fresh robot in the same module still gives the fresh module's answers.
  const last = load();
  cases.forEach((c, k) => assert.deepEqual(last.solve(c), solved[k], `final solve of case ${k} (${where()})`));
  last.delete();
  assert.ok(checks > 0, `no result was compared (${ops} operations)`);
  console.log(`boundary property test: ${ops} operations, ${checks} results compared, seed ${SEED}`);
});
