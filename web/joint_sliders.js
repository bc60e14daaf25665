// One slider per joint of the robot shown: a limited joint over its URDF limits, a
// continuous (or unlimited revolute) joint over a full turn, -pi to pi, an unlimited
// prismatic joint over +-UNLIMITED_PRISMATIC m. Moving a slider hands the whole
// configuration to `onPose(q)` (the page pauses and sets q there); "Start pose" hands over
// the robot's start pose. While the simulation runs, the sliders follow q (a continuous
// joint's angle shown wrapped into -pi..pi).

const UNLIMITED_PRISMATIC = 0.5;
// Positions per slider: fine enough that a drag looks continuous.
const STEPS = 2000;

export class JointSliders {
  // list: the element the sliders go in; startButton: the "Start pose" button.
  constructor(list, startButton, { onPose, startPose }) {
    this.list = list;
    this.onPose = onPose;
    this.sliders = [];
    this.q = [];
    startButton.addEventListener('click', () => {
      const q = startPose();
      if (q) this.onPose([...q]);
    });
  }

  // robot: an achd robot (jointNames, jointTypes, limits); q: its configuration now. A
  // floating base's free joint has no slider (its 7 numbers come first in q).
  setRobot(robot, q) {
    const first = robot.floating ? 1 : 0;
    this.sliders = robot.jointNames.slice(first).map((name, i) => {
      const j = i + first;
      const at = robot.floating ? j + 6 : j;  // the joint's index in q
      const { low, high } = sliderRange(robot.limits[j], robot.jointTypes[j]);
      const input = document.createElement('input');
      input.type = 'range';
      input.min = String(low);
      input.max = String(high);
      input.step = String((high - low) / STEPS);
      input.dataset.joint = name;
      input.setAttribute('aria-label', `joint ${name}`);
      const value = document.createElement('output');
      const unit = robot.jointTypes[j] === 'prismatic' ? 'm' : 'rad';
      input.addEventListener('input', () => {
        const next = [...this.q];
        next[at] = Number(input.value);
        this.onPose(next);
      });
      const label = document.createElement('label');
      const title = document.createElement('span');
      title.className = 'joint-name';
      title.textContent = name;
      title.title = `${robot.jointTypes[j]}, ${low.toFixed(3)} to ${high.toFixed(3)} ${unit}`;
      label.append(title, input, value);
      return { input, value, unit, at, wrap: !Number.isFinite(robot.limits[j].lower) && robot.jointTypes[j] !== 'prismatic' };
    });
    this.list.replaceChildren(...this.sliders.map((s) => s.input.parentElement));
    this.show(q);
  }

  // Shows configuration q on the sliders.
  show(q) {
    this.q = Array.from(q);
    this.sliders.forEach((s) => {
      const v = s.wrap ? wrapAngle(this.q[s.at]) : this.q[s.at];
      if (document.activeElement !== s.input) s.input.value = String(v);
      s.value.textContent = `${this.q[s.at].toFixed(2)} ${s.unit}`;
    });
  }
}

function sliderRange(limit, type) {
  if (Number.isFinite(limit.lower) && Number.isFinite(limit.upper)) return { low: limit.lower, high: limit.upper };
  return type === 'prismatic' ? { low: -UNLIMITED_PRISMATIC, high: UNLIMITED_PRISMATIC } : { low: -Math.PI, high: Math.PI };
}

// The angle in -pi..pi that is the same turn as a.
function wrapAngle(a) {
  return a - 2 * Math.PI * Math.round(a / (2 * Math.PI));
}
