// The page's first module: assigns window.achdDemo before anything waits, then loads the
// wasm module, the robot index and the robot from the URL hash (or the default), and
// simulates in real time: each animation frame steps as many dt as wall time elapsed.
//
// Recovery: a failed step pauses the page and shows the error (the state stays at the
// last good step); Reset clears the error, the events and the plots, restores the start
// pose with the toggles kept, and plays again if the page was playing when the step
// failed. Loading a robot (the list, an own URDF) frees every direction, clears the
// events and the plots, and plays.
//
// Loop joints: a robot of the list comes with its loops file's loops; two Alt-clicks
// close one more (a fixed loop joint between the two links as they are then), and the
// loops card opens it again. The core holds loops as part of the model, so either loads
// the robot again with the other loops and goes on from the same state (web/simulation.js,
// carryOn).
import { ChainView } from './chain_view.js';
import { Controls } from './controls.js';
import { EventsNotice } from './events_notice.js';
import { ForceArrows } from './force_arrows.js';
import { JointSliders } from './joint_sliders.js';
import { LinkHover } from './link_hover.js';
import { LinkSelect } from './link_select.js';
import { PickedFiles, ServedFiles } from './mesh_files.js';
import { keepMeshes, openKeptMeshes } from './mesh_share.js';
import { moduleOffer } from './module_offer.js';
import { PushDrag } from './push_drag.js';
import { Readouts } from './readouts.js';
import { DIRECTIONS, GRAVITY, adoptOffer, checkDirection, defaultSettings, formatHash, hashOwn, hashRobot, motionFrom, parseHash,
  sameClosed, sameOwn } from './settings.js';
import { Simulation, jointControlOf } from './simulation.js';
import { TorqueBars } from './torque_bars.js';
import { UrdfUpload } from './urdf_upload.js';
import { LINK_CHARACTERS, openSharedSrdf, openSharedUrdf, shareSrdf, shareUrdf, urdfKey } from './urdf_share.js';
import { linkVisuals } from './link_visuals.js';
import { fixedLoopBetween } from './loop_pick.js';
import './accuracy_panel.js';

// At most this much simulated time per frame: after a stall (a hidden tab, a slow
// frame) the simulation resumes instead of trying to catch up all at once.
const MAX_FRAME_SECONDS = 0.25;
const NUMBERS_EVERY_MS = 200;
const SOLVE_TIMING_EVERY_MS = 1000;
const RATE_WINDOW_MS = 1000;
const CUSTOM = 'custom';
// What the page calls an own URDF opened from a link (its file name is not in the link).
const LINKED_NAME = 'The URDF of the link';
// The arrows' scale (web/force_arrows.js) takes the robot's weight and size: at least
// these, for a URDF with massless or tiny links.
const MIN_MASS = 0.1;
const MIN_REACH = 0.2;

const page = {
  achd: null,
  offer: null,
  index: null,
  sim: null,
  links: null,
  settings: null,
  playing: true,
  owed: 0,
  lastFrame: null,
  lastNumbers: 0,
  lastSolveTiming: -Infinity,
  rate: { wall: 0, sim: 0, shown: null },
  pushedLink: null,
  // A push given by achdDemo.push ({link: FK index, wrench}), applied as a drag's is.
  scriptedPush: null,
  writtenHash: '',
  // The last failed step: {message, wasPlaying}, until Reset or a new robot.
  failure: null,
  // The robot's visuals: {meshes: outcomes of web/chain_view.js's setChain (null while
  // they load), problems: visuals the URDF has but that could not be read}.
  look: { meshes: [], problems: [] },
  // The last own URDF loaded ({name: CUSTOM, text, root, tip, fileName, files}): the robot
  // list's "own URDF" entry reopens it.
  ownSource: null,
  // How the link holds the own URDF shown: {form: 'link' | 'local', ref, characters, key,
  // meshes: {named, files, bytes, error}} (web/urdf_share.js, web/mesh_share.js), or
  // {error}; null while it is worked out (its meshes are read first), and for a robot of
  // the list.
  share: null,
  // The first link of a loop being closed by picking (its name), until the second pick.
  loopPick: null,
}

let markReady;
let failReady;
const ready = new Promise((resolve, reject) => {
  markReady = resolve;
  failReady = reject;
});
// Awaiting `ready` still sees a failure; this only keeps an unobserved one off the console.
ready.catch(() => {});
let isReady = false;

// Lines the wasm module prints (urdfdom's parse errors): kept for the page's message
// instead of the console.
const moduleLog = [];

window.achdDemo = {
  ready,
  state() {
    if (!page.sim) throw new Error('achdDemo.state: no robot loaded yet (await achdDemo.ready)');
    return {
      ...page.sim.snapshot(),
      playing: page.playing,
      error: page.failure?.message ?? null,
      events: notice.recent.map((e) => ({ ...e })),
      lost: [...notice.lostOn(page.sim.selected)],
      plots: readouts.plotRanges(),
      look: { meshes: page.look.meshes?.map((m) => ({ ...m })) ?? null, problems: [...page.look.problems] },
      share: page.share && { ...page.share },
      warnings: [...page.sim.robot.warnings],
      floating: page.sim.robot.floating,
      pose: page.sim.pose,
      loopPick: page.loopPick,
    };
  },
  // The robot shown as it was loaded: {name, text (its URDF), root, tip, q0 (start pose),
  // and loadURDF's other options: floating, mimic, inertia, srdf (text), pose (the pose
  // chosen last; null for none)}.
  robotSource() {
    if (!page.sim) throw new Error('achdDemo.robotSource: no robot loaded yet (await achdDemo.ready)');
    const s = page.sim.source;
    return { name: s.name, title: s.fileName ?? robotSelect.selectedOptions[0]?.text ?? s.name, text: s.text,
      root: page.sim.robot.root, tip: page.sim.robot.tip, q0: [...page.sim.q0], floating: page.sim.robot.floating,
      mimic: s.mimic ?? null, inertia: s.inertia ?? null, srdf: s.srdf ?? null, pose: page.sim.pose,
      loops: structuredClone([...(s.loops ?? []), ...(s.closed ?? [])]) };
  },
  // Closes a loop between two links by name, as Alt-clicks on link_a, then link_b, do: a
  // fixed loop joint holding their relative pose now. Throws (after the page has shown it)
  // when the loader refuses the loop; the robot then runs on without it.
  closeLoop(linkA, linkB) {
    if (!page.sim) throw new Error('achdDemo.closeLoop: no robot loaded yet (await achdDemo.ready)');
    closeLoop(linkA, linkB);
  },
  // Opens a loop the user closed (by its name, state().loops), as its Open button does.
  openLoop(name) {
    if (!page.sim) throw new Error('achdDemo.openLoop: no robot loaded yet (await achdDemo.ready)');
    openLoop(name);
  },
  // Each loop joint's closure error, m or rad: {name: {now, max}} (sim.loopDrift()).
  loopDrift() {
    if (!page.sim) throw new Error('achdDemo.loopDrift: no robot loaded yet (await achdDemo.ready)');
    return page.sim.sim.loopDrift();
  },
  // The 3D view's camera (column-major 4x4 matrices as three.js stores them), the
  // canvas's size in CSS pixels and its place on the page, and the box the camera framed
  // last ({min, max}, world, m: web/chain_view.js's frameCamera), or null without WebGL.
  camera() {
    if (!view.enabled) return null;
    const rect = view.renderer.domElement.getBoundingClientRect();
    view.camera.updateMatrixWorld();
    return {
      projection: [...view.camera.projectionMatrix.elements],
      worldInverse: [...view.camera.matrixWorldInverse.elements],
      rect: { left: rect.left, top: rect.top, width: rect.width, height: rect.height },
      box: view.framed && { min: [...view.framed.min], max: [...view.framed.max] },
    };
  },
  // A direction of the selected link (selectLink chooses it; a chain starts with its tip).
  setDirection(name, mode) {
    checkDirection(name, mode);
    if (!page.sim) throw new Error('achdDemo.setDirection: no robot loaded yet (await achdDemo.ready)');
    setDirection(name, mode);
  },
  // The link whose directions the controls show and setDirection sets, as a click on it
  // does; with `point` ([x, y, z] in the link's frame, as a Shift-click picks one) its
  // directions act there.
  selectLink(name, point) {
    if (!page.sim) throw new Error('achdDemo.selectLink: no robot loaded yet (await achdDemo.ready)');
    selectLink(name, point);
  },
  // Where a link's directions act, in the base frame (world for a floating base), m.
  pointPosition(name) {
    if (!page.sim) throw new Error('achdDemo.pointPosition: no robot loaded yet (await achdDemo.ready)');
    if (!page.sim.robot.linkNames.includes(name)) throw new Error(`achdDemo.pointPosition: no link "${name}"`);
    return page.sim.pointOf(name, page.sim.links());
  },
  // A link's origin in the base frame (world for a floating base), m.
  linkPosition(name) {
    if (!page.sim) throw new Error('achdDemo.linkPosition: no robot loaded yet (await achdDemo.ready)');
    const link = page.sim.links().find((l) => l.name === name);
    if (!link) throw new Error(`achdDemo.linkPosition: no link "${name}"`);
    return link.position;
  },
  // A joint on a motion ({motion: 'constant' | 'ramp' | 'sine', position, velocity,
  // amplitude, frequency}, started now), or null: driven by its torques again.
  setPrescribed(joint, params) {
    if (!page.sim) throw new Error('achdDemo.setPrescribed: no robot loaded yet (await achdDemo.ready)');
    setPrescribed(joint, params);
  },
  // Whether a direction yields to pushes (w_fext = 0).
  setYield(name, on) {
    checkDirection(name, 'free');
    if (!page.sim) throw new Error('achdDemo.setYield: no robot loaded yet (await achdDemo.ready)');
    setYield(name, Boolean(on));
  },
  // The constraint wrench the view draws at the selected link and its two arrows' ends
  // (base frame): {wrench, metersPerNewton, metersPerNewtonMeter, force: {shown, from, to,
  // length}, moment: {...}, links: {name: {wrench, force, moment}} for every constrained
  // link}, and the torque bars: [{joint, torque, effort, fraction, over}].
  forces() {
    if (!page.sim) throw new Error('achdDemo.forces: no robot loaded yet (await achdDemo.ready)');
    return { ...arrows.drawn(), torques: torqueBars.state() };
  },
  // The tip link's origin in the base frame, m.
  tipPosition() {
    if (!page.sim) throw new Error('achdDemo.tipPosition: no robot loaded yet (await achdDemo.ready)');
    return page.sim.links().at(-1).position;
  },
  // A wrench (base axes, about the link origin) on a link by name, as a drag applies one;
  // null stops it.
  push(link, wrench) {
    if (!page.sim) throw new Error('achdDemo.push: no robot loaded yet (await achdDemo.ready)');
    if (link === null) {
      page.scriptedPush = null;
      return;
    }
    const index = page.sim.robot.linkNames.indexOf(link);
    if (index < 0) throw new Error(`achdDemo.push: no link "${link}" on the chain`);
    page.scriptedPush = { link: index + 1, wrench: Array.from(wrench) };
  },
  play() {
    setPlaying(true);
  },
  pause() {
    setPlaying(false);
  },
  step(n = 1) {
    if (!Number.isInteger(n) || n < 1) throw new Error(`achdDemo.step: n must be a positive integer, got ${n}`);
    if (!page.sim) throw new Error('achdDemo.step: no robot loaded yet (await achdDemo.ready)');
    stepSimulation(n);
  },
  // Starts again from the SRDF pose `name` (null: none), as the pose list does.
  choosePose(name) {
    if (!page.sim) throw new Error('achdDemo.choosePose: no robot loaded yet (await achdDemo.ready)');
    choosePose(name);
  },
  // Puts the robot at rest at q (an array in joint order), paused, as the sliders do.
  setPose(q) {
    if (!page.sim) throw new Error('achdDemo.setPose: no robot loaded yet (await achdDemo.ready)');
    setPose(Array.from(q));
  },
  // An own URDF as the load form loads it: tip null (or left out) for the whole robot;
  // options {floating, mimic, inertia, srdf (text), pose}.
  async loadURDF(text, root, tip, options = {}) {
    await ready;
    const { floating, mimic, inertia, srdf, pose } = options;
    loadRobot({ name: CUSTOM, text: String(text), root, tip: tip ?? null, floating, mimic, inertia, srdf, pose });
  },
};

const errorBox = document.getElementById('page-error');
const errorText = document.getElementById('page-error-text');
document.getElementById('page-error-close').addEventListener('click', () => {
  errorBox.hidden = true;
});
function showError(message) {
  errorText.textContent = message;
  errorBox.hidden = false;
}

const view = new ChainView(document.getElementById('view'));
const notice = new EventsNotice(document.getElementById('sim-events-list'), document.getElementById('sim-events-none'));
const arrows = new ForceArrows(view);
const torqueBars = new TorqueBars(document.getElementById('torque-bars'));
const readouts = new Readouts(document.getElementById('numbers'), document.getElementById('plots'));
const push = new PushDrag(view, {
  canPush: (link) => Boolean(page.sim) && link > 0 && page.settings.effects.externalWrenches,
  linkPose: (link) => page.links[link],
  stiffness: () => page.sim.pushStiffness(),
  maxForce: () => page.sim.pushMaxForce(),
});
const controls = new Controls({
  playPause: () => setPlaying(!page.playing),
  step: () => {
    setPlaying(false);
    try {
      if (page.sim) stepSimulation(1);
    } catch {
      // A failed step is on the page already (stepSimulation shows it).
    }
  },
  reset: () => resetSimulation(),
  integrator: (v) => changeSetting(() => (page.settings.integrator = v), true),
  rtol: (v) => changeSetting(() => (page.settings.rtol = v), true),
  dt: (v) => changeSetting(() => (page.settings.dt = v), false),
  policy: (v) => changeSetting(() => (page.settings.policy = v), true),
  limits: (v) => changeSetting(() => (page.settings.limits = v), true),
  direction: (name, mode) => setDirection(name, mode),
  yield: (name, on) => setYield(name, on),
  prescribe: (joint, params) => {
    try {
      setPrescribed(joint, params);
    } catch (err) {
      showError(`joint ${joint}: ${err.message}`);
    }
  },
  effect: (key, on) => changeSetting(() => (page.settings.effects[key] = on), true),
});
new LinkHover(view, document.getElementById('link-label'), (link) => page.links?.[link]?.name,
  (x, y) => arrows.describe(x, y));
new LinkSelect(view, (link, at) => {
  const name = page.links?.[link]?.name;
  if (!page.sim || link === 0 || !name) return;  // the root takes no directions
  try {
    // A Shift-click's world point, in the link's frame: p_link = R^T (p - o).
    let point;
    if (at) {
      const { position: o, rotation: R } = page.links[link];
      const d = [at.x - o[0], at.y - o[1], at.z - o[2]];
      point = [0, 1, 2].map((j) => R[j] * d[0] + R[3 + j] * d[1] + R[6 + j] * d[2]);
    }
    selectLink(name, point);
  } catch (err) {
    showError(err.message);
  }
}, (link) => {
  const name = page.links?.[link]?.name;
  if (!page.sim || !name) return;
  if (page.loopPick === null) {
    page.loopPick = name;
    showLoops();
    return;
  }
  try {
    if (page.loopPick === name) {
      page.loopPick = null;  // the same link again: no loop
      showLoops();
    } else {
      closeLoop(page.loopPick, name);
    }
  } catch {
    // On the page already (closeLoop shows it).
  }
});
const viewNote = document.getElementById('view-note');
const sliders = new JointSliders(document.getElementById('joint-sliders'), document.getElementById('btn-start-pose'), {
  onPose: (q) => {
    try {
      setPose(q);
    } catch (err) {
      showError(`could not set the pose: ${err.message}`);
    }
  },
  startPose: () => page.sim?.q0,
});
const upload = new UrdfUpload({
  onLoad: (choice) => {
    try {
      loadRobot({ name: CUSTOM, ...choice });
      upload.hide();
    } catch (err) {
      showError(`${choice.fileName}: ${err.message}`);
    }
  },
  onError: (err) => showError(err.message),
});
const robotSelect = document.getElementById('robot-select');
robotSelect.addEventListener('change', () => selectRobot(robotSelect.value));
// The SRDF poses of the robot shown (robot.poses): choosing one starts again from it.
const NO_POSE = '';
const poseSelect = document.getElementById('pose-select');
poseSelect.addEventListener('change', () => {
  try {
    choosePose(poseSelect.value === NO_POSE ? null : poseSelect.value);
  } catch (err) {
    showError(`could not choose the pose: ${err.message}`);
    showPoses();
  }
});

function setPlaying(on) {
  page.playing = on;
  page.lastFrame = null;
  page.owed = 0;
  if (page.settings) controls.show(page.settings, on);
}

function setDirection(name, mode) {
  page.settings.directions[name] = mode;
  if (page.sim) page.sim.applyDirection(name);
  notice.forget(page.sim.selected, name);
  controls.showLost(notice.lostOn(page.sim.selected));
  controls.show(page.settings, page.playing);
  writeHash();
}

// The controls show (and set) the directions of `name`; the other links keep theirs. With
// a point (link frame), its directions act there.
function selectLink(name, point) {
  page.sim.select(name);
  if (point) page.sim.setPoint(name, point);
  page.settings.link = name === page.sim.robot.tip ? null : name;
  controls.showLost(notice.lostOn(name));
  controls.show(page.settings, page.playing);
  showSelected();
  writeHash();
}

function showSelected() {
  document.getElementById('directions-link').textContent = page.sim.selected;
}

// The robot at rest at q, paused (the sliders, "Start pose"); time, events and plots go on.
function setPose(q) {
  setPlaying(false);
  push.release();
  page.sim.setPose(q);
  page.links = page.sim.links();
  sliders.show(page.sim.q);
}

// A fixed loop joint between two links as they are now (web/loop_pick.js), the robot
// loaded again with it; the loader's refusal is shown and the robot runs on as it was.
function closeLoop(linkA, linkB) {
  page.loopPick = null;
  try {
    const taken = new Set(page.sim.robot.loops.map((l) => l.name));
    const loop = fixedLoopBetween(page.sim.links(), linkA, linkB, taken);
    reloadLoops([...(page.sim.source.closed ?? []), loop]);
  } catch (err) {
    showLoops();
    showError(`could not close a loop between ${linkA} and ${linkB}: ${err.message}`);
    throw err;
  }
}

function openLoop(name) {
  const closed = page.sim.source.closed ?? [];
  if (!closed.some((l) => l.name === name)) throw new Error(`no loop "${name}" closed on the page`);
  reloadLoops(closed.filter((l) => l.name !== name));
}

// The robot shown, loaded again with `closed` as the loops the user closed: the same
// state, settings, directions, prescribed joints, time and plots (web/simulation.js,
// carryOn). Throws, the robot shown kept, when the loader refuses.
function reloadLoops(closed) {
  const sim = new Simulation(page.achd, { ...page.sim.source, closed }, page.settings, page.sim);
  push.release();
  page.pushedLink = null;
  page.sim.delete();
  page.sim = sim;
  page.links = sim.links();
  torqueBars.setRobot(sim.robot);
  sliders.setRobot(sim.robot, sim.q);
  showLoops();
  page.settings.closed = closed;
  writeHash();
}

// The loops card: each loop joint of the robot shown (its links, type and held
// directions), an Open button beside those the user closed, and what an Alt-click does next.
function showLoops() {
  const list = document.getElementById('loop-list');
  const closed = page.sim.source.closed ?? [];
  list.replaceChildren(...page.sim.robot.loops.map((loop) => {
    const item = document.createElement('li');
    item.dataset.loop = loop.name;
    const picked = closed.some((c) => c.name === loop.name);
    item.textContent = `${loop.name}: ${loop.type}, ${loop.link_a} to ${loop.link_b}, holds ${loop.directions.join(' ')}` +
      `${picked ? ' (closed here)' : ''} `;
    if (picked) {
      const button = document.createElement('button');
      button.type = 'button';
      button.textContent = 'Open';
      button.dataset.open = loop.name;
      button.addEventListener('click', () => {
        try {
          openLoop(loop.name);
        } catch (err) {
          showError(`could not open the loop ${loop.name}: ${err.message}`);
        }
      });
      item.append(button);
    }
    return item;
  }));
  document.getElementById('loops-none').hidden = page.sim.robot.loops.length > 0;
  document.getElementById('loop-pick').textContent = page.loopPick === null
    ? 'Alt-click a link, then another, to close a loop between them.'
    : `Closing a loop from ${page.loopPick}: Alt-click the second link (${page.loopPick} again: no loop).`;
}

function setYield(name, on) {
  page.settings.yielding[name] = on;
  page.sim.applyYield(name);
  controls.show(page.settings, page.playing);
  writeHash();
}

// params null: the joint is free again; else its motion starts now, where it is.
function setPrescribed(joint, params) {
  if (!page.sim.robot.jointNames.includes(joint)) throw new Error(`no movable joint "${joint}" on the chain`);
  const before = page.settings.prescribed[joint];
  if (params === null) delete page.settings.prescribed[joint];
  else page.settings.prescribed[joint] = motionFrom(params, page.sim.t);
  try {
    page.sim.applyPrescribed(joint);
  } catch (err) {
    if (before) page.settings.prescribed[joint] = before;
    else delete page.settings.prescribed[joint];
    throw err;
  }
  controls.show(page.settings, page.playing);
}

// The pose list: robot.poses of the robot shown (hidden when its SRDF gave none, or it
// came without one), the pose it started from chosen.
function showPoses() {
  const names = Object.keys(page.sim.robot.poses);
  poseSelect.replaceChildren(new Option('none (joints at 0 or mid-limits)', NO_POSE),
    ...names.map((name) => new Option(name, name)));
  poseSelect.value = page.sim.pose ?? NO_POSE;
  document.getElementById('pose-select-label').hidden = !names.length;
}

// Starts again from an SRDF pose (null: none) as if the robot had been loaded in it
// (web/simulation.js, choosePose): its directions the robot's defaults, no prescribed
// joints, the time, events and plots cleared; playing or paused as before. The link
// names the pose.
function choosePose(name) {
  const sim = page.sim;
  push.release();
  page.pushedLink = null;
  page.scriptedPush = null;
  sim.choosePose(name);
  page.settings.link = sim.selected === sim.robot.tip ? null : sim.selected;
  showSelected();
  controls.setJoints(sim.robot.floating ? sim.robot.jointNames.slice(1) : sim.robot.jointNames, jointPosition);
  clearRun();
  setPlaying(page.playing);
  page.links = sim.links();
  arrows.setRobot(reachOf(page.links), Math.hypot(...GRAVITY) * Math.max(sim.mass, MIN_MASS));
  sliders.show(sim.q);
  showPoses();
  if (page.settings.own) page.settings.own = { ...page.settings.own, pose: sim.pose };
  writeHash();
}

// A joint's position now (controls.setJoints reads where a prescribed motion starts).
function jointPosition(joint) {
  if (!page.sim) return null;
  const j = page.sim.robot.jointNames.indexOf(joint);
  return page.sim.sim.q[page.sim.robot.floating ? j + 6 : j];
}

// Back to the start pose, toggles kept (a held direction holds where the tip is then);
// after a failure, also out of it: the error goes, and the page plays again if it was
// playing when the step failed.
function resetSimulation() {
  if (!page.sim) return;
  push.release();
  page.pushedLink = null;
  page.sim.reset();
  const resume = page.failure?.wasPlaying ?? page.playing;
  clearRun();
  setPlaying(resume);
}

// Forgets what the previous run showed: the failure, the events and the plots.
function clearRun() {
  page.failure = null;
  errorBox.hidden = true;
  notice.clear();
  controls.showLost(notice.lostOn(page.sim?.selected));
  readouts.clear();
}

// Effects and the integrator are fixed in a simulator: changing them rebuilds it from
// the current state (held directions hold where the tip is then).
function changeSetting(apply, rebuild) {
  apply();
  if (page.sim && rebuild) {
    push.release();
    page.pushedLink = null;
    page.sim.rebuild();
  }
  controls.show(page.settings, page.playing);
  writeHash();
}

function writeHash() {
  page.writtenHash = formatHash(page.settings);
  if (location.hash !== page.writtenHash) history.replaceState(null, '', page.writtenHash);
}

// Replaces the robot; on failure the previous one keeps running and the Error (with
// what urdfdom printed) propagates to the caller, which shows it. The new robot starts
// with every direction free, unless keepDirections (a robot named by the URL hash, whose
// directions come with it).
function loadRobot(source, { keepDirections = false } = {}) {
  moduleLog.length = 0;
  let sim;
  // Prescribed joints are the old robot's: the new one starts with none.
  const prescribed = page.settings.prescribed;
  page.settings.prescribed = {};
  try {
    sim = new Simulation(page.achd, source, page.settings);
  } catch (err) {
    page.settings.prescribed = prescribed;
    const detail = moduleLog.filter((line) => !err.message.includes(line.trim())).join('\n');
    const message = `could not load the robot: ${err.message}${detail ? '\n' + detail : ''}`;
    showError(message);
    throw new Error(message);
  }
  push.release();
  page.pushedLink = null;
  page.sim?.delete();
  page.sim = sim;
  page.settings.robot = source.name;
  // A link of the hash (link=) is selected with the hash's directions; the default links
  // of a tree are held, the others free.
  if (keepDirections && page.settings.link && sim.robot.linkNames.includes(page.settings.link)) {
    const directions = { ...page.settings.directions }, yielding = { ...page.settings.yielding };
    sim.selected = page.settings.link;
    sim.defaultDirections();
    Object.assign(page.settings.directions, directions);
    Object.assign(page.settings.yielding, yielding);
  } else if (keepDirections) {
    const directions = { ...page.settings.directions }, yielding = { ...page.settings.yielding };
    sim.defaultDirections();
    if (sim.robot.tip) {
      Object.assign(page.settings.directions, directions);
      Object.assign(page.settings.yielding, yielding);
    }
  } else {
    sim.defaultDirections();
  }
  page.settings.link = sim.selected === sim.robot.tip ? null : sim.selected;
  sim.applyDrivers();
  showSelected();
  page.scriptedPush = null;
  const movableJoints = sim.robot.floating ? sim.robot.jointNames.slice(1) : sim.robot.jointNames;
  controls.setJoints(movableJoints, jointPosition);
  clearRun();
  setPlaying(true);
  page.links = sim.links();
  page.owed = 0;
  // Real time starts one step ago, so that the next frame already steps.
  page.lastFrame = performance.now() - 1000 * page.settings.dt;
  page.lastSolveTiming = -Infinity;
  page.rate = { wall: 0, sim: 0, shown: null };
  const looked = showLook(sim, source);
  arrows.setRobot(reachOf(page.links), Math.hypot(...GRAVITY) * Math.max(sim.mass, MIN_MASS));
  torqueBars.setRobot(sim.robot);
  sliders.setRobot(sim.robot, sim.q);
  showPoses();
  page.loopPick = null;
  showLoops();
  if (source.name === CUSTOM && ![...robotSelect.options].some((o) => o.value === CUSTOM)) {
    robotSelect.add(new Option(`own URDF`, CUSTOM));
  }
  robotSelect.value = source.name;
  errorBox.hidden = true;
  showWarnings(sim.robot.warnings);
  page.settings.closed = source.closed ?? [];
  if (source.name === CUSTOM) {
    page.ownSource = source;
    shareOwn(sim, source, looked);
  } else {
    page.settings.own = null;
    page.share = null;
    showShareNote(source);
  }
  writeHash();
}

// What the loader found odd in the URDF but loaded (robot.warnings), under the robot list.
function showWarnings(warnings) {
  const note = document.getElementById('robot-warnings');
  note.hidden = !warnings.length;
  note.textContent = warnings.length ? `Loaded with ${warnings.length} warning${warnings.length > 1 ? 's' : ''}:\n` +
    warnings.join('\n') : '';
}

// Puts the own URDF in the page's link (in it, or kept in this browser's storage and named
// by it: web/urdf_share.js) once its meshes are read (looked: the promise of their
// outcomes), keeps the mesh files read in this browser's storage under the URDF's key
// (web/mesh_share.js), and says on the page which.
function shareOwn(sim, source, looked) {
  page.settings.own = null;
  page.share = null;
  showShareNote(source);
  shareUrdf(source.text).then(async (share) => {
    // Its SRDF (cut to its group_states by the picker; a link's own is cut already) goes
    // the same way, so that the link's robot has the same poses to choose from.
    if (source.srdf) share.srdf = await shareSrdf(source.srdfShared ?? source.srdf);
    const meshes = await looked;
    if (page.sim !== sim || !meshes) return;
    share.meshes = await keepOwnMeshes(share.key, source, meshes);
    if (page.sim !== sim) return;
    page.settings.own = { ref: share.ref, root: sim.robot.root, tip: sim.robot.tip, floating: sim.robot.floating,
      mimic: source.mimic ?? null, inertia: source.inertia ?? null, srdf: share.srdf?.ref ?? null, pose: sim.pose };
    page.share = share;
    writeHash();
    showShareNote(source);
  }, (err) => {
    if (page.sim !== sim) return;
    page.share = { error: err.message };
    showShareNote(source);
  });
}

// -> {named: mesh visuals, files: mesh and texture files kept, bytes, error}. A URDF with
// meshes keeps the files they were read from; with none of them read, the key forgets
// its files (the link then shows what this page shows); without meshes nothing changes.
async function keepOwnMeshes(key, source, meshes) {
  const kept = { named: meshes.length, files: 0, bytes: 0, error: source.meshesUnread ?? null };
  if (!meshes.length || kept.error || !(source.files instanceof PickedFiles)) return kept;
  try {
    return { ...kept, ...(await keepMeshes(key, source.files)) };
  } catch (err) {
    return { ...kept, error: err.message };
  }
}

// Where the link keeps the SRDF an own URDF came with, in words (empty without one).
function srdfNote(srdf) {
  if (!srdf) return '';
  return srdf.form === 'link' ? ' Its SRDF\'s poses travel in the link too.'
    : ` Its SRDF's poses are kept in this browser's storage (${srdf.ref}): the link has them in this browser only.`;
}

// What the link keeps of an own URDF's meshes, in words (empty without meshes).
function meshesNote({ named, files, bytes, error }, key) {
  if (!named) return '';
  if (error) return ` Its mesh files are not kept for the link (${error}): it reopens without them.`;
  if (!files) return ' None of its mesh files was read here, so the link reopens it without them.';
  return ` Its ${files} mesh file${files > 1 ? 's' : ''} (${(bytes / 1024).toFixed(1)} kB) ${files > 1 ? 'are' : 'is'} ` +
    `kept in this browser's storage (IndexedDB, key ${key}): the link shows ${files > 1 ? 'them' : 'it'} in this browser only, ` +
    'another draws a stick figure instead.';
}

function showShareNote(source) {
  const note = document.getElementById('share-note');
  note.hidden = source.name !== CUSTOM;
  if (note.hidden) return;
  const name = source.fileName ?? 'The own URDF';
  const s = page.share;
  note.classList.toggle('share-failed', Boolean(s?.error));
  note.textContent = !s ? `${name}: preparing its link…`
    : s.error ? `${name}: ${s.error}.`
      : (s.form === 'link' ? `${name} travels in this page's link (${s.characters} characters, compressed): ` +
        'the address opens it in any browser.'
        : `${name} is kept in this browser's storage and this page's link names it (${s.ref}): the address ` +
          `reopens it in this browser only (compressed it takes ${s.characters} characters, more than the ` +
          `${LINK_CHARACTERS} a link carries).`) + srdfNote(s.srdf) + meshesNote(s.meshes, s.key);
}

// The robot's size for the arrows' scale: the farthest link origin from the root at the
// start pose, at least MIN_REACH.
function reachOf(links) {
  const root = links[0].position;
  return links.reduce((r, l) => Math.max(r, Math.hypot(...l.position.map((x, k) => x - root[k]))), MIN_REACH);
}

// Builds the robot in the view from its URDF's visuals (meshes from source.files) and
// says on the page which meshes were not found or not read, and which visuals not parsed.
// Returns the promise of the meshes' outcomes (null when another robot came first).
function showLook(sim, source) {
  let look = null;
  let problems = [];
  try {
    look = linkVisuals(sim.robot);
    problems = look.problems;
    look.files = source.files;
  } catch (err) {
    problems = [err.message];
  }
  page.look = { meshes: null, problems };
  showLookNote();
  return view.setChain(page.links, sim.movable, sim.parents, look).then((meshes) => {
    if (!meshes || page.sim !== sim) return null;  // another robot came first
    page.look.meshes = meshes;
    showLookNote();
    return meshes;
  });
}

function showLookNote() {
  const lines = [];
  const meshes = page.look.meshes ?? [];
  const missing = [...new Set(meshes.filter((m) => m.status === 'missing').map((m) => m.filename))];
  const failed = meshes.filter((m) => m.status === 'failed');
  if (missing.length) {
    lines.push(`Meshes not found (a stick figure stands in for their links): ${missing.join(', ')}. ` +
      'Load the robot\'s folder (Load folder…, or drop it) so that package:// and relative paths resolve.');
  }
  for (const m of failed) lines.push(`Mesh ${m.filename} of link ${m.link} not shown: ${m.message}.`);
  for (const m of meshes.filter((m) => m.texturesMissing?.length)) {
    lines.push(`Textures of ${m.filename} not found (drawn without): ${m.texturesMissing.join(', ')}.`);
  }
  for (const p of page.look.problems) lines.push(`Visual left out: ${p}.`);
  viewNote.textContent = lines.join('\n');
  viewNote.hidden = !lines.length;
}

async function fetchText(path) {
  // Index paths are relative to the repository root, one level above web/.
  const response = await fetch(new URL(`../${path}`, import.meta.url));
  if (!response.ok) throw new Error(`${path}: HTTP ${response.status}`);
  return response.text();
}

// Meshes of a robot of robots/index.json are read next to its URDF on this server.
function servedFiles(entry) {
  return new ServedFiles(new URL(`../${entry.urdf}`, import.meta.url));
}

async function selectRobot(name, options) {
  if (name === CUSTOM && page.ownSource) {
    try {
      loadRobot(page.ownSource, options);
    } catch {
      robotSelect.value = page.settings.robot;  // shown by loadRobot
    }
    return;
  }
  const entry = page.index.robots.find((r) => r.name === name);
  if (!entry) return;
  try {
    const [text, loops] = await Promise.all([fetchText(entry.urdf), fetchLoops(entry)]);
    loadRobot(indexSource(entry, text, loops), options);
  } catch (err) {
    robotSelect.value = page.settings.robot;
    showError(`${entry.name}: ${err.message}`);
  }
}

function stepSimulation(n) {
  const p = push.current() ?? page.scriptedPush;
  if (p) {
    page.sim.setPush(p.link, p.wrench);
    page.pushedLink = p.link;
  } else if (page.pushedLink !== null) {
    page.sim.setPush(page.pushedLink, null);
    page.pushedLink = null;
  }
  try {
    page.sim.step(n);
  } catch (err) {
    // The simulator kept the last good step; the page pauses there and says why.
    page.failure = { message: `the simulation stopped: ${err.message}`, wasPlaying: page.playing };
    setPlaying(false);
    showError(`${page.failure.message}\nReset starts again from the start pose.`);
    throw err;
  } finally {
    showEvents();
  }
  if (!isReady) {
    isReady = true;
    // The moment the page started stepping, for anyone timing the page's start-up.
    performance.mark('achd:stepping');
    markReady();
  }
}

function showEvents() {
  const fresh = page.sim.newEvents();
  if (!fresh.length) return;
  notice.add(fresh);
  controls.showLost(notice.lostOn(page.sim.selected));
}

// Frames read performance.now(), not rAF's frame start time, which can precede the
// moment a robot was loaded and would delay its first step by a frame.
function frame() {
  const now = performance.now();
  requestAnimationFrame(frame);
  const sim = page.sim;
  if (!sim) return;
  try {
    if (page.playing) {
      if (page.lastFrame !== null) {
        const wall = Math.min((now - page.lastFrame) / 1000, MAX_FRAME_SECONDS);
        page.owed += wall;
        const dt = page.settings.dt;
        const n = Math.floor(page.owed / dt);
        if (n > 0) {
          const t0 = sim.t;
          stepSimulation(n);
          page.owed -= n * dt;
          page.rate.sim += sim.t - t0;
        }
        page.rate.wall += (now - page.lastFrame) / 1000;
        if (page.rate.wall * 1000 >= RATE_WINDOW_MS) {
          page.rate.shown = page.rate.sim / page.rate.wall;
          page.rate.wall = 0;
          page.rate.sim = 0;
        }
      }
      page.lastFrame = now;
    }
    if (now - page.lastSolveTiming >= SOLVE_TIMING_EVERY_MS) {
      sim.measureSolve();
      page.lastSolveTiming = now;
    }
    page.links = sim.links();
    // The last solve's numbers first, so that the arrows drawn are this state's.
    readouts.sample(sim);
    const last = readouts.last;
    if (last) {
      arrows.update(sim.wrenches(page.links), sim.selected);
      torqueBars.show(last.torques, now);
    }
    const p = push.current();
    view.update(page.links, page.settings.directions, p && { from: p.from, to: p.to },
      1 + sim.robot.linkNames.indexOf(sim.selected), sim.pointOf(sim.selected, page.links));
    view.updateLoops(sim.loopEnds(page.links));
    view.render();
    readouts.drawCharts();
    if (now - page.lastNumbers >= NUMBERS_EVERY_MS) {
      page.lastNumbers = now;
      readouts.showNumbers();
      sliders.show(sim.q);
      document.getElementById('readout-time').textContent = `t = ${sim.t.toFixed(2)} s`;
      document.getElementById('readout-rtf').textContent = !page.playing ? 'paused'
        : page.rate.shown === null ? '' : `running at ${page.rate.shown.toFixed(2)}× real time`;
    }
  } catch (err) {
    // A failed step is already shown (stepSimulation); anything else stops the page too.
    if (!page.failure) {
      setPlaying(false);
      showError(`the page stopped: ${err.message}`);
    }
  }
}

// A shared link edited by hand (or the back button) applies without a reload.
window.addEventListener('hashchange', () => {
  if (!page.index || location.hash === page.writtenHash) return;
  const { settings, problems } = parseHash(location.hash, defaultSettings(page.index.default, page.offer), page.offer);
  const robot = settings.robot;
  // The robot and own URDF shown stay in the settings until another one has loaded.
  const linked = settings.own, closed = settings.closed;
  settings.robot = page.settings.robot;
  settings.own = page.settings.own;
  settings.closed = page.settings.closed;
  // Another selected link: the robot is built again with it (its directions, the others'
  // defaults), as when the page opens on the link.
  const shownLink = page.sim && page.sim.selected !== page.sim.robot.tip ? page.sim.selected : null;
  const otherLink = page.sim && (settings.link ?? null) !== shownLink;
  Object.assign(page.settings, settings);
  if (!otherLink) page.sim?.rebuild();
  controls.show(page.settings, page.playing);
  if (problems.length) showError(`ignored in the URL: ${problems.join('; ')}`);
  if (robot === CUSTOM && linked && !sameOwn(linked, page.settings.own)) openLinkedUrdf(linked);
  else if (robot !== page.settings.robot || otherLink) selectRobot(robot, { keepDirections: true });
  else if (!sameClosed(closed, page.settings.closed)) reloadLinkedLoops(closed);
  else writeHash();
});

// The loops an edited link closes on the robot shown; the loader's refusal is shown and
// the robot runs on as it was.
function reloadLinkedLoops(closed) {
  try {
    reloadLoops(closed);
  } catch (err) {
    showError(`ignored in the URL: closed: ${err.message}`);
    writeHash();
  }
}

// The source of the own URDF a link names (urdf=, root=, tip=, base=, and the loader's
// options mimic=, inertia=, srdf=, pose=), with the mesh files this browser keeps for it
// (web/mesh_share.js; none in another browser). Throws when the URDF or its SRDF cannot
// be had; storage that cannot be read leaves the meshes out (meshesUnread says why).
async function linkedSource(own) {
  const text = await openSharedUrdf(own.ref);
  const srdf = own.srdf ? await openSharedSrdf(own.srdf) : undefined;
  const source = { name: CUSTOM, text, root: own.root, tip: own.tip, floating: own.floating, fileName: LINKED_NAME,
    files: null, mimic: own.mimic ?? undefined, inertia: own.inertia ?? undefined, srdf, pose: own.pose ?? undefined };
  try {
    source.files = await openKeptMeshes(await urdfKey(text));
  } catch (err) {
    source.meshesUnread = `this browser's storage could not be read: ${err.message}`;
  }
  return source;
}

// An own URDF named by an edited link, with the link's directions.
async function openLinkedUrdf(own) {
  try {
    loadRobot(await linkedSource(own), { keepDirections: true });
  } catch (err) {
    showError(`the own URDF of the link: ${err.message}`);
    writeHash();
  }
}

async function loadModule() {
  let createAchd;
  try {
    ({ default: createAchd } = await import('./dist/achd.mjs'));
  } catch (err) {
    throw new Error(`web/dist/achd.mjs did not load (${err.message}); build it with ` +
      '`cmake --preset wasm && cmake --build --preset wasm`');
  }
  return createAchd({ print: (line) => moduleLog.push(line), printErr: (line) => moduleLog.push(line) });
}

// The index and the first robot's URDF load while the wasm module compiles.
async function readIndexAndRobot() {
  const index = JSON.parse(await fetchText('robots/index.json'));
  const problems = [];
  let robot = hashRobot(location.hash, index.default);
  if (robot === CUSTOM) {
    const own = hashOwn(location.hash);
    try {
      if (!own) throw new Error(`robot=${CUSTOM} needs urdf= and root=`);
      const { text, ...entry } = await linkedSource(own);
      return { index, problems, entry, text, loops: undefined };
    } catch (err) {
      problems.push(`the own URDF of the link: ${err.message}`);
      robot = index.default;
    }
  }
  if (!index.robots.some((r) => r.name === robot)) {
    problems.push(`robot "${robot}" is not in robots/index.json`);
    robot = index.default;
  }
  const entry = index.robots.find((r) => r.name === robot);
  const [text, loops] = await Promise.all([fetchText(entry.urdf), fetchLoops(entry)]);
  return { index, problems, entry, text, loops };
}

// The loop joints of an index robot: the "loops" list of its loops file (entry.loops, a
// path like urdf's), or undefined without one.
async function fetchLoops(entry) {
  return entry.loops ? JSON.parse(await fetchText(entry.loops)).loops : undefined;
}

// The source of an index robot (loops: its loops file's), its meshes read from this server.
function indexSource(entry, text, loops) {
  return { name: entry.name, text, root: entry.root, tip: entry.tip, q0: entry.q0, files: servedFiles(entry),
    floating: entry.floating, mimic: entry.mimic, constraints: entry.constraints, held: entry.held,
    jointControl: jointControlOf(entry.joint_control), loops };
}

// A robot of the link with the loops the link closed (closed=); when the loader refuses
// them, the robot without them, and why in problems.
function loadWithClosed(source, problems) {
  const closed = page.settings.closed;
  if (!closed.length) return loadRobot(source, { keepDirections: true });
  try {
    loadRobot({ ...source, closed }, { keepDirections: true });
  } catch (err) {
    problems.push(`closed: ${err.message}`);
    loadRobot(source, { keepDirections: true });
  }
}

async function start() {
  const [achd, { index, problems, entry, text, loops }] = await Promise.all([loadModule(), readIndexAndRobot()]);
  page.achd = achd;
  page.offer = moduleOffer(achd);
  adoptOffer(page.offer);
  page.index = index;
  for (const r of index.robots) robotSelect.add(new Option(r.title, r.name));
  const parsed = parseHash(location.hash, defaultSettings(entry.name, page.offer), page.offer);
  page.settings = { ...parsed.settings, robot: entry.name };
  problems.push(...parsed.problems);
  controls.offer(page.offer);
  controls.show(page.settings, page.playing);
  try {
    loadWithClosed(entry.name === CUSTOM ? { ...entry, text } : indexSource(entry, text, loops), problems);
  } catch (err) {
    // An own URDF of the link that does not load: the default robot instead, and why.
    if (entry.name !== CUSTOM) throw err;
    problems.push(err.message);
    const fallback = index.robots.find((r) => r.name === index.default);
    page.settings.robot = fallback.name;
    loadRobot(indexSource(fallback, await fetchText(fallback.urdf), await fetchLoops(fallback)), { keepDirections: true });
  }
  if (problems.length) showError(`ignored in the URL: ${problems.join('; ')}`);
  requestAnimationFrame(frame);
}

start().catch((err) => {
  showError(`the page could not start: ${err.message}`);
  failReady(err);
});
