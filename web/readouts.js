// Live numbers and plots under the view: residual per held direction and nu of the
// selected link, the loop joints' closure errors, joint torques, energy, and the time one
// step and one solve take in this browser.
import { DIRECTION_COLORS } from './chain_view.js';
import { DIRECTIONS } from './settings.js';
import { StripChart } from './strip_chart.js';

const JOINT_COLORS = ['#2f6fdf', '#d9443a', '#2e9e4f', '#e58a1f', '#8b4fd1', '#1a9aa0', '#a0522d', '#5d6677'];
const PLOTTED_JOINTS = JOINT_COLORS.length;

const fmt = (v, digits = 4) => (v === null || v === undefined || Number.isNaN(v) ? '–' : Number(v).toPrecision(digits));
const list = (values, digits = 3) => values.map((v) => fmt(v, digits)).join('  ');

export class Readouts {
  constructor(table, plots) {
    this.rows = {};
    for (const [key, label] of [
      ['t', 'time t'], ['energy', 'energy (kinetic + gravity)'], ['step', 'one step'],
      ['solve', 'one solve'], ['capacity', 'real-time capacity'], ['residuals', 'held residuals'],
      ['nu', 'ν (constraint forces)'], ['loops', 'loop closure (now, largest)'], ['torques', 'joint torques'],
    ]) {
      const tr = table.insertRow();
      const th = document.createElement('th');
      th.textContent = label;
      tr.append(th);
      this.rows[key] = tr.insertCell();
    }
    this.charts = {
      residuals: new StripChart(plots, 'held residuals, m or rad (log10 |e|)', { log: true }),
      nu: new StripChart(plots, 'ν, N or N m'),
      torques: new StripChart(plots, 'joint torques, N m or N'),
      energy: new StripChart(plots, 'energy, J'),
      timing: new StripChart(plots, 'time per step and per solve, µs'),
    };
    this.charts.energy.setSeries([{ label: 'kinetic + potential', color: '#2f6fdf' }]);
    this.charts.timing.setSeries([
      { label: 'step', color: '#d9443a' },
      { label: 'solve', color: '#2e9e4f' },
    ]);
    this.signature = '';
    this.sampledAt = null;
  }

  // Empties every plot and the numbers (a reset, a new robot): nothing of the previous
  // run stays on an axis.
  clear() {
    for (const chart of Object.values(this.charts)) chart.clear();
    this.sampledAt = null;
    this.last = null;
  }

  // Series follow the robot and the constrained directions; a change restarts them.
  configure(sim) {
    const constrained = DIRECTIONS.filter((d) => sim.settings.directions[d] !== 'free');
    const held = constrained.filter((d) => sim.settings.directions[d] === 'hold');
    const signature = `${sim.robot.jointNames.join()}|${sim.selected}|${constrained.join()}|${held.join()}`;
    if (signature === this.signature) return;
    this.signature = signature;
    this.constrained = constrained;
    this.held = held;
    this.charts.residuals.setSeries(held.map((d) => ({ label: d, color: DIRECTION_COLORS[d] })));
    this.charts.nu.setSeries(constrained.map((d) => ({ label: d, color: DIRECTION_COLORS[d] })));
    const joints = sim.robot.jointNames.slice(0, PLOTTED_JOINTS);
    const more = sim.robot.numRates - joints.length;
    this.charts.torques.setSeries(joints.map((j, i) => ({ label: i === joints.length - 1 && more ? `${j} (+${more} not plotted)` : j, color: JOINT_COLORS[i] })));
  }

  // One sample per animation frame in which the simulation moved: while it is paused (or
  // stopped by a failure) the plots keep the run up to that moment instead of filling
  // with copies of its last state.
  sample(sim) {
    this.configure(sim);
    if (this.last?.sim === sim && this.sampledAt === sim.t) return;
    this.sampledAt = sim.t;
    const residuals = sim.sim.residuals(sim.selected);
    const nu = sim.nuByLink()[sim.selected] ?? [];
    const torques = sim.sim.joint_torques();
    const energy = sim.sim.energy();
    // {loop name: {now, max}}: each loop joint's closure error, m or rad
    const loops = sim.sim.loopDrift();
    // constrained: the selected link's constrained directions, in the order of its nu.
    this.last = { sim, residuals, nu, torques, energy, loops, constrained: this.constrained };
    this.charts.residuals.push(this.held.map((d) => residuals[d]));
    // a link's nu lists its constraints in direction order, as the simulator builds alpha.
    this.charts.nu.push(this.constrained.map((_, k) => nu[k]));
    this.charts.torques.push(torques.slice(0, PLOTTED_JOINTS));
    this.charts.energy.push([energy.total]);
    this.charts.timing.push([sim.currentStepMicros() ?? NaN, sim.solveMicros ?? NaN]);
  }

  drawCharts() {
    for (const chart of Object.values(this.charts)) chart.draw();
  }

  // Per plot, the span of the samples it shows and their number ({lo, hi, samples}; lo
  // and hi in log10 for the residuals), or null when it shows none.
  plotRanges() {
    return Object.fromEntries(Object.entries(this.charts).map(([name, chart]) => [name, chart.drawn && { ...chart.drawn }]));
  }

  showNumbers() {
    if (!this.last) return;
    const { sim, residuals, nu, torques, energy, loops } = this.last;
    const stepMicros = sim.currentStepMicros();
    this.rows.t.textContent = `${sim.t.toFixed(3)} s`;
    this.rows.energy.textContent = `${fmt(energy.total, 6)} J  (kinetic ${fmt(energy.kinetic, 4)})`;
    this.rows.step.textContent = stepMicros === null ? '–' : `${stepMicros.toFixed(1)} µs (${sim.settings.integrator})`;
    this.rows.solve.textContent = sim.solveMicros === null ? '–' : `${sim.solveMicros.toFixed(2)} µs`;
    this.rows.capacity.textContent = stepMicros === null ? '–'
      : `${((1e6 * sim.settings.dt) / stepMicros).toFixed(1)} simulated s per wall s at dt = ${sim.settings.dt * 1000} ms`;
    this.rows.residuals.textContent = this.held.length
      ? this.held.map((d) => `${d}: ${residuals[d].toExponential(2)}`).join('  ') : 'no held direction';
    this.rows.nu.textContent = this.constrained.length
      ? this.constrained.map((d, k) => `${d}: ${fmt(nu[k], 4)}`).join('  ') : 'no constraint';
    const closures = Object.entries(loops);
    this.rows.loops.textContent = closures.length
      ? closures.map(([name, e]) => `${name}: ${e.now.toExponential(2)}, ${e.max.toExponential(2)}`).join('  ')
      : 'no loop joint';
    this.rows.torques.textContent = list(torques);
  }
}
