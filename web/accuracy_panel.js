// The page's "accuracy" panel: on a button press, the accuracy-versus-time study of
// `achd accuracy` (tools/accuracy_study.hpp) run live with the wasm module on the robot
// the page shows, short: each integrator the module has (achd.constants.integrators),
// the fixed-step ones at dt = 10, 5, 2, 1, 0.5 ms and the adaptive one at 10 ms output
// steps once per tolerance, over 0.5 s from the robot's start pose with the page's held
// directions and the simulator's default effects and policy; error = max|q(T) - q_ref(T)|
// (rad) against RK4 at 0.125 ms (whose own error, the change when its step is halved, is
// shown), cost = median of 3 timed runs per step. Beside it: the native figures of the
// README (docs/accuracy/arm7). The live runs are plotted and listed in a table. Nothing
// runs until the button is pressed.
import { isAdaptive } from './settings.js';

const DURATION = 0.5;
const STEPS_MS = [10, 5, 2, 1, 0.5];
const ADAPTIVE_MS = 10;
const RTOLS = [1e-3, 1e-5, 1e-7, 1e-9];
const REFERENCE_MS = 0.125;
const TIMING_RUNS = 3;
const TIMING_STEPS = 200;
// A timed run steps on, TIMING_STEPS at a time, until it has taken this long: far above
// the browser's timer resolution (performance.now() is coarsened to 0.1 ms without
// cross-origin isolation), so that even a tiny robot's time per step is not 0.
const TIMING_MIN_MS = 5;
const UNSTABLE_ERROR = 1; // rad: larger errors (or NaN) are reported as unstable
// Names and colours the panel knows; any other integrator the module offers is plotted
// under its own name in grey.
const LOOKS = {
  explicit_euler: { label: 'explicit Euler', color: '#d62728' },
  semi_implicit_euler: { label: 'semi-implicit Euler', color: '#1f77b4' },
  implicit_euler: { label: 'implicit Euler', color: '#9467bd' },
  rk4: { label: 'RK4', color: '#2ca02c' },
  dormand_prince: { label: 'Dormand-Prince', color: '#ff7f0e' },
};
const looks = (name) => ({ name, ...(LOOKS[name] ?? { label: name, color: '#7f7f7f' }) });
const NATIVE = '../docs/accuracy/arm7/accuracy.json';
const SVG_NS = 'http://www.w3.org/2000/svg';

const panel = document.getElementById('accuracy-panel');
if (panel) mount(panel);

function mount(root) {
  root.innerHTML = `
    <h2>Accuracy versus time</h2>
    <p>Each fixed-step integrator at dt = ${STEPS_MS.join(', ')} ms and the adaptive one at
      ${ADAPTIVE_MS} ms output steps for rtol = ${RTOLS.map((r) => r.toExponential(0)).join(', ')},
      for ${DURATION} s on the current robot with every effect on (the equations do not
      depend on the step), error against an RK4 reference at ${REFERENCE_MS} ms, cost
      measured in this browser. <button type="button" class="accuracy-run">Run the study</button></p>
    <p class="accuracy-status" aria-live="polite"></p>
    <div class="accuracy-columns" style="display: flex; flex-wrap: wrap; gap: 1em; align-items: flex-start">
      <figure class="accuracy-live"></figure>
      <figure class="accuracy-native"><figcaption>Native (README, 7-DoF arm holding z and rx, 2 s)</figcaption>
        <img src="../docs/accuracy/arm7/accuracy.svg" alt="native accuracy plot" width="380">
        <table class="accuracy-native-table"></table></figure>
    </div>`;
  const status = root.querySelector('.accuracy-status');
  const button = root.querySelector('.accuracy-run');
  button.addEventListener('click', async () => {
    button.disabled = true;
    status.textContent = 'running…';
    try {
      const study = await runStudy((text) => (status.textContent = text));
      root.querySelector('.accuracy-live').replaceChildren(plot(study.integrators, study.runs), runsTable(study.runs));
      status.textContent =
        `${study.robot}: reference self-check (halving its step) ${study.selfError.toExponential(1)} rad; ` +
        `unstable: ${study.runs.filter((r) => !r.stable).map((r) => `${r.label} ${r.at}`).join(', ') || 'none'}; ` +
        `study took ${(study.wallMs / 1000).toFixed(1)} s.`;
    } catch (err) {
      status.textContent = `the study failed: ${err.message}`;
    } finally {
      button.disabled = false;
    }
  });
  showNative(root.querySelector('.accuracy-native-table'));
}

// The robot of the page (one of robots/index.json or an own URDF, as it was loaded) in a
// separate module instance, so the page's own simulator keeps its state.
async function loadRobot() {
  await window.achdDemo.ready;
  const state = window.achdDemo.state();
  const source = window.achdDemo.robotSource();
  const { default: createAchd } = await import('./dist/achd.mjs');
  const achd = await createAchd();
  const robot = achd.loadURDF(source.text, { root: source.root, tip: source.tip, loops: source.loops });
  const held = Object.entries(state.directions).filter(([, mode]) => mode !== 'free');
  return { name: source.title, robot, q0: source.q0, held, integrators: achd.constants.integrators.map(looks) };
}

// The runs of the study: a fixed-step integrator once per step of STEPS_MS, an adaptive
// one once per tolerance at ADAPTIVE_MS. `options` are createSimulator's.
function plannedRuns(integrators) {
  return integrators.flatMap((integrator) => (isAdaptive(integrator.name)
    ? RTOLS.map((rtol) => ({ integrator, ms: ADAPTIVE_MS, point: rtol.toExponential(0),
      options: { integrator: integrator.name, rtol } }))
    : STEPS_MS.map((ms) => ({ integrator, ms, point: String(ms), options: { integrator: integrator.name } }))));
}

function endState(robot, setup, options, dt) {
  const sim = robot.createSimulator(options);
  try {
    sim.reset(setup.q0);
    for (const [direction, mode] of setup.held) sim.setDirection(direction, mode);
    sim.step(Math.round(DURATION / dt), dt);
    return { q: Array.from(sim.q) };
  } catch (err) {
    return { q: null, error: err.message }; // the solver refused a diverged state
  } finally {
    sim.delete();
  }
}

// Median over TIMING_RUNS runs of ms per step, each run TIMING_STEPS steps at a time until
// it took TIMING_MIN_MS (or diverged: then the time per step taken, 0 when below the
// timer's resolution).
function msPerStep(robot, setup, options, dt) {
  const sim = robot.createSimulator(options);
  const samples = [];
  try {
    for (let r = 0; r < TIMING_RUNS; ++r) {
      sim.reset(setup.q0);
      for (const [direction, mode] of setup.held) sim.setDirection(direction, mode);
      const t0 = performance.now();
      try {
        do {
          sim.step(TIMING_STEPS, dt);
        } while (performance.now() - t0 < TIMING_MIN_MS);
      } catch {
        // a diverging run stops early; its time per step taken still counts
      }
      samples.push((performance.now() - t0) / Math.max(1, Math.round(sim.t / dt)));
    }
  } finally {
    sim.delete();
  }
  samples.sort((a, b) => a - b);
  return samples[Math.floor(samples.length / 2)];
}

const maxAbsDifference = (a, b) => Math.max(...a.map((v, i) => Math.abs(v - b[i])));
// Lets the page draw the status and handle input between runs. A message on a channel,
// not requestAnimationFrame or setTimeout: a page that is not visible gets no animation
// frames and throttled timers, and the study would stall there.
const nextTask = () => new Promise((resolve) => {
  const { port1, port2 } = new MessageChannel();
  port1.onmessage = () => {
    port1.close();
    resolve();
  };
  port2.postMessage(null);
});

async function runStudy(report) {
  const wall0 = performance.now();
  const setup = await loadRobot();
  try {
    report('reference…');
    await nextTask();
    const ref = endState(setup.robot, setup, { integrator: 'rk4' }, REFERENCE_MS / 1000).q;
    const half = endState(setup.robot, setup, { integrator: 'rk4' }, REFERENCE_MS / 2000).q;
    if (!ref || !half) throw new Error('the RK4 reference did not stay finite');
    const runs = [];
    for (const { integrator, ms, point, options } of plannedRuns(setup.integrators)) {
      const at = isAdaptive(integrator.name) ? `rtol ${point}` : `${ms} ms`;
      report(`${integrator.label} at ${at}…`);
      await nextTask();
      const dt = ms / 1000;
      const { q } = endState(setup.robot, setup, options, dt);
      const error = q && q.every(Number.isFinite) ? maxAbsDifference(q, ref) : Infinity;
      const perStep = msPerStep(setup.robot, setup, options, dt);
      runs.push({ integrator: integrator.name, label: integrator.label, color: integrator.color, ms, point, at, error,
        stable: error <= UNSTABLE_ERROR, msPerStep: perStep, cost: perStep / 1000 / dt });
    }
    markPareto(runs.filter((r) => r.stable));
    return { robot: setup.name, integrators: setup.integrators, runs, selfError: maxAbsDifference(ref, half),
      wallMs: performance.now() - wall0 };
  } finally {
    setup.robot.delete();
  }
}

// A point is on the front unless another is no worse in cost and error and better in one.
function markPareto(points) {
  for (const p of points)
    p.pareto = !points.some((o) => o !== p && o.cost <= p.cost && o.error <= p.error &&
      (o.cost < p.cost || o.error < p.error));
}

// Log-log error (rad) against cost (s per simulated s), as the native SVG.
function plot(integrators, runs) {
  const W = 580, H = 320, L = 64, R = 190, T = 12, B = 44;
  // Only positive finite values have a place on log axes (a range of decades from -Infinity
  // would never end).
  const shown = runs.filter((r) => r.stable && r.error > 0 && r.cost > 0 && Number.isFinite(r.cost));
  const decades = (values) => {
    const lo = Math.floor(Math.log10(Math.min(...values)));
    return [lo, Math.max(lo + 1, Math.ceil(Math.log10(Math.max(...values))))];
  };
  const [x0, x1] = decades([...shown.map((r) => r.cost), 1]);
  const [y0, y1] = decades(shown.map((r) => r.error));
  const px = (x) => L + ((Math.log10(x) - x0) / (x1 - x0)) * (W - L - R);
  const py = (y) => T + (1 - (Math.log10(y) - y0) / (y1 - y0)) * (H - T - B);
  const svg = el('svg', { width: W, height: H, viewBox: `0 0 ${W} ${H}`, 'font-size': 11, 'font-family': 'sans-serif' });
  for (let k = x0; k <= x1; ++k) {
    svg.append(el('line', { x1: px(10 ** k), x2: px(10 ** k), y1: T, y2: H - B, stroke: '#ddd' }));
    svg.append(text(px(10 ** k), H - B + 14, `1e${k}`, { 'text-anchor': 'middle' }));
  }
  for (let k = y0; k <= y1; ++k) {
    svg.append(el('line', { x1: L, x2: W - R, y1: py(10 ** k), y2: py(10 ** k), stroke: '#ddd' }));
    svg.append(text(L - 4, py(10 ** k) + 4, `1e${k}`, { 'text-anchor': 'end' }));
  }
  svg.append(el('line', { x1: px(1), x2: px(1), y1: T, y2: H - B, stroke: '#888', 'stroke-dasharray': '6 4' }));
  svg.append(text(px(1) - 4, H - B - 6, 'real time', { fill: '#555', 'text-anchor': 'end' }));
  svg.append(text((L + W - R) / 2, H - 8, 'cost: wall time per simulated second (s/s)', { 'text-anchor': 'middle' }));
  svg.append(text(14, (T + H - B) / 2, 'error: max |q(T) − q_ref(T)| (rad)',
    { 'text-anchor': 'middle', transform: `rotate(-90 14 ${(T + H - B) / 2})` }));
  integrators.forEach((integrator, i) => {
    const points = shown.filter((r) => r.integrator === integrator.name);
    svg.append(el('polyline', { fill: 'none', stroke: integrator.color, 'stroke-width': 2,
      points: points.map((r) => `${px(r.cost)},${py(r.error)}`).join(' ') }));
    for (const r of points) {
      svg.append(el('circle', { cx: px(r.cost), cy: py(r.error), r: 3.5, fill: integrator.color }));
      if (r.pareto) svg.append(el('circle', { cx: px(r.cost), cy: py(r.error), r: 7, fill: 'none', stroke: 'black' }));
      svg.append(text(px(r.cost) + 5, py(r.error) - 5, r.point, { 'font-size': 9, fill: '#444' }));
    }
    svg.append(el('circle', { cx: W - R + 20, cy: T + 10 + 16 * i, r: 4, fill: integrator.color }));
    svg.append(text(W - R + 32, T + 14 + 16 * i, integrator.label));
  });
  const below = T + 10 + 16 * integrators.length;
  svg.append(el('circle', { cx: W - R + 20, cy: below, r: 7, fill: 'none', stroke: 'black' }));
  svg.append(text(W - R + 32, below + 4, 'Pareto front'));
  svg.append(text(W - R + 12, below + 26, 'labels: dt in ms,', { fill: '#555' }));
  svg.append(text(W - R + 12, below + 40, 'adaptive: rtol', { fill: '#555' }));
  return svg;
}

// Every run of the live study as a table, as the native one beside it.
function runsTable(runs) {
  const table = document.createElement('table');
  table.className = 'accuracy-live-table';
  table.innerHTML = '<tr><th>integrator</th><th>step</th><th>error (rad)</th><th>µs/step</th><th>cost (s/s)</th></tr>' +
    runs.map((r) => `<tr><td>${r.label}</td><td>${r.at}</td>` +
      `<td>${r.stable ? r.error.toExponential(1) : 'unstable'}</td>` +
      `<td>${(r.msPerStep * 1000).toFixed(1)}</td><td>${r.cost.toExponential(1)}</td></tr>`).join('');
  return table;
}

function el(name, attributes) {
  const node = document.createElementNS(SVG_NS, name);
  for (const [k, v] of Object.entries(attributes)) node.setAttribute(k, v);
  return node;
}

function text(x, y, content, attributes = {}) {
  const node = el('text', { x, y, ...attributes });
  node.textContent = content;
  return node;
}

// The integrator ladder of the native study as a table (stable runs).
async function showNative(table) {
  try {
    const response = await fetch(NATIVE);
    if (!response.ok) throw new Error(`${NATIVE}: HTTP ${response.status}`);
    const study = await response.json();
    const rows = study.runs.filter((r) => r.kind === 'integrator');
    table.innerHTML = '<tr><th>integrator</th><th>dt (ms)</th><th>error (rad)</th><th>µs/step</th></tr>' +
      rows.map((r) => `<tr><td>${r.integrator}</td><td>${r.dt_s * 1e3}</td>` +
        `<td>${r.stable ? r.error_q_rad.toExponential(1) : 'unstable'}</td>` +
        `<td>${(r.ns_per_step / 1000).toFixed(1)}</td></tr>`).join('');
  } catch (err) {
    table.innerHTML = `<tr><td>native figures unavailable: ${err.message}</td></tr>`;
  }
}
