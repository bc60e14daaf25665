// The constraint wrench of each constrained link, alpha nu of the simulator's last solve
// (sim.constraintWrenches()), drawn as two arrows from the link's origin: the force f
// (linear part, N) and the moment m (angular part, N m, a double-headed arrow along its
// axis, the usual notation for a moment). It is the wrench the link exerts on the
// constraint; the robot receives -alpha nu.
//
// Scale, fixed per robot so that a length reads as a value: an arrow of length
// `reach / 2` stands for the robot's weight W = m g (the force) or W * reach (the moment),
// so length = |f| * reach / (2 W) and |m| / (2 W). Arrows are drawn over the robot
// (no depth test), unlit, in colours no direction glyph uses. Updating them each frame
// sets transforms only: arrows are made only when more links are constrained than ever
// before on this robot.
import * as THREE from 'three';

export const FORCE_COLOR = '#c2185b';
export const MOMENT_COLOR = '#5e35b1';
const UP = new THREE.Vector3(0, 1, 0);  // three's cylinders and cones are built along +y
// Below this length (m) an arrow is not drawn: no direction to show.
const SHORTEST = 1e-9;

class Arrow {
  // heads: 1 (a force) or 2 (a moment); radius: the shaft's, m; order: three's renderOrder,
  // the higher drawn later, over the other.
  constructor(color, heads, radius, order) {
    const material = new THREE.MeshBasicMaterial({ color, depthTest: false, depthWrite: false, transparent: true });
    this.group = new THREE.Group();
    this.group.renderOrder = order;
    this.headLength = radius * 7;
    this.shaft = new THREE.Mesh(new THREE.CylinderGeometry(radius, radius, 1, 12), material);
    this.heads = [];
    const cone = new THREE.ConeGeometry(radius * 2.6, 1, 16);
    for (let k = 0; k < heads; k++) this.heads.push(new THREE.Mesh(cone, material));
    for (const mesh of [this.shaft, ...this.heads]) {
      mesh.renderOrder = order;
      this.group.add(mesh);
    }
    this.group.visible = false;
    this.length = 0;
  }

  // From `origin` along `vector` (a THREE.Vector3, modified: normalised) for `length` m;
  // the heads take their share of the length, so the arrow ends exactly there.
  set(origin, vector, length) {
    this.length = length;
    this.group.visible = length > SHORTEST;
    if (!this.group.visible) return;
    this.group.position.copy(origin);
    this.group.quaternion.setFromUnitVectors(UP, vector.normalize());
    const heads = this.heads.length;
    const head = Math.min(this.headLength, length / (heads + 1));
    const shaft = length - heads * head;
    this.shaft.scale.set(1, shaft, 1);
    this.shaft.position.set(0, shaft / 2, 0);
    // Heads stacked at the end, the last one's point at `length`.
    this.heads.forEach((mesh, k) => {
      mesh.scale.set(1, head, 1);
      mesh.position.set(0, shaft + head * (k + 0.5), 0);
    });
  }

  dispose() {
    for (const mesh of [this.shaft, ...this.heads]) mesh.geometry.dispose();
    this.shaft.material.dispose();
  }
}

export class ForceArrows {
  // view: the ChainView whose scene the arrows go in.
  constructor(view) {
    this.view = view;
    this.enabled = view.enabled;
    this.scratch = new THREE.Vector3();
    this.origin = new THREE.Vector3();
    this.metersPerNewton = 0;
    this.metersPerNewtonMeter = 0;
    // One pair per constrained link drawn: {name, wrench, force, moment}; grown, not shrunk.
    this.pairs = [];
    this.shown = 0;
    this.selected = null;
    this.group = null;
  }

  // A new robot: reach (m, its size) and weight (N).
  setRobot(reach, weight) {
    this.metersPerNewton = reach / (2 * weight);
    this.metersPerNewtonMeter = 1 / (2 * weight);
    for (const pair of this.pairs) {
      pair.force?.dispose();
      pair.moment?.dispose();
    }
    this.pairs = [];
    this.shown = 0;
    if (!this.enabled) return;
    if (this.group) this.view.scene.remove(this.group);
    this.group = new THREE.Group();
    this.view.scene.add(this.group);
  }

  pair(k) {
    while (this.pairs.length <= k) {
      const pair = { name: '', wrench: new Float64Array(6), force: null, moment: null };
      if (this.enabled && this.group) {
        const radius = this.view.radius * 0.55;
        // The force over the moment: both start at the link's origin, and the moment's two
        // heads would hide a short force arrow.
        pair.force = new Arrow(FORCE_COLOR, 1, radius, 11);
        pair.moment = new Arrow(MOMENT_COLOR, 2, radius * 0.8, 10);
        this.group.add(pair.force.group, pair.moment.group);
      }
      this.pairs.push(pair);
    }
    return this.pairs[k];
  }

  // links: [{name, position: [x, y, z] (the link's origin), wrench: [6] (alpha nu, base
  // axes)}] of the last solve, one per constrained link; selected: the link whose arrows
  // drawn() reports first.
  update(links, selected) {
    this.selected = selected;
    links.forEach((link, k) => {
      const pair = this.pair(k);
      pair.name = link.name;
      pair.wrench.set(link.wrench);
      if (!pair.force) return;
      const w = pair.wrench;
      this.origin.fromArray(link.position);
      this.scratch.set(w[0], w[1], w[2]);
      pair.force.set(this.origin, this.scratch, this.scratch.length() * this.metersPerNewton);
      this.scratch.set(w[3], w[4], w[5]);
      pair.moment.set(this.origin, this.scratch, this.scratch.length() * this.metersPerNewtonMeter);
    });
    for (let k = links.length; k < this.pairs.length; k++) this.clear(this.pairs[k]);
    this.shown = links.length;
  }

  clear(pair) {
    pair.wrench.fill(0);
    pair.name = '';
    if (pair.force) {
      pair.force.group.visible = false;
      pair.moment.group.visible = false;
    }
  }

  hide() {
    for (const pair of this.pairs) this.clear(pair);
    this.shown = 0;
  }

  // What is drawn, for tests and the hover: the selected link's wrench and its arrows'
  // ends in the base frame (from the meshes' world matrices) and whether they show, and
  // the same for every constrained link drawn (`links`, by name).
  drawn() {
    const ends = (arrow) => {
      if (!arrow) return { shown: false, from: null, to: null, length: 0 };
      arrow.group.updateMatrixWorld(true);
      const from = new THREE.Vector3().setFromMatrixPosition(arrow.group.matrixWorld);
      const to = new THREE.Vector3(0, arrow.length, 0).applyMatrix4(arrow.group.matrixWorld);
      return { shown: arrow.group.visible, from: from.toArray(), to: to.toArray(), length: from.distanceTo(to) };
    };
    const of = (pair) => ({ wrench: Array.from(pair?.wrench ?? new Float64Array(6)), force: ends(pair?.force),
      moment: ends(pair?.moment) });
    const drawn = this.pairs.slice(0, this.shown);
    return {
      ...of(drawn.find((p) => p.name === this.selected)),
      metersPerNewton: this.metersPerNewton,
      metersPerNewtonMeter: this.metersPerNewtonMeter,
      links: Object.fromEntries(drawn.map((p) => [p.name, of(p)])),
    };
  }

  // The text for the pointer at (clientX, clientY) when it is over a shown arrow, else null.
  describe(clientX, clientY) {
    if (!this.enabled || !this.group) return null;
    this.view.ray(clientX, clientY);
    const hit = this.view.raycaster.intersectObject(this.group, true).find((h) => visible(h.object));
    if (!hit) return null;
    const pair = this.pairs.find((p) => [p.force?.group, p.moment?.group].some((g) => isAncestor(g, hit.object)));
    if (!pair) return null;
    const w = pair.wrench;
    const f = Math.hypot(w[0], w[1], w[2]);
    const m = Math.hypot(w[3], w[4], w[5]);
    const v = (a, b, c) => `(${fmt(a)}, ${fmt(b)}, ${fmt(c)})`;
    return `constraint wrench α ν at ${pair.name} (on the constraint; the robot receives −α ν)\n` +
      `force ${v(w[0], w[1], w[2])} N, |f| = ${fmt(f)} N\n` +
      `moment ${v(w[3], w[4], w[5])} N m, |m| = ${fmt(m)} N m\n` +
      `scale: 1 N = ${fmt(1000 * this.metersPerNewton)} mm, 1 N m = ${fmt(1000 * this.metersPerNewtonMeter)} mm`;
  }
}

function isAncestor(group, object) {
  for (let o = object; o; o = o.parent) if (o === group) return true;
  return false;
}

const fmt = (v) => Number(v).toPrecision(3);

function visible(object) {
  for (let o = object; o; o = o.parent) if (!o.visible) return false;
  return true;
}
