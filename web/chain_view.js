// The 3D view: the robot as its URDF's visuals on the link frames forward kinematics
// reports (web/visual_meshes.js), or, for a URDF without visuals and for links whose mesh
// was not found, a stick figure: simple solids between consecutive link frames and
// spheres at movable joints. Also the tip frame's axes, the held or accelerated tip
// directions as glyphs, and the loop joints. z is up, as in URDF.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { DIRECTIONS } from './settings.js';
import { placementMatrix, visualObject } from './visual_meshes.js';

export const DIRECTION_COLORS = {
  x: '#d9443a', y: '#2e9e4f', z: '#2f6fdf', rx: '#e58a1f', ry: '#1a9aa0', rz: '#8b4fd1',
};
const AXES = {
  x: new THREE.Vector3(1, 0, 0), y: new THREE.Vector3(0, 1, 0), z: new THREE.Vector3(0, 0, 1),
  rx: new THREE.Vector3(1, 0, 0), ry: new THREE.Vector3(0, 1, 0), rz: new THREE.Vector3(0, 0, 1),
};
const UP = new THREE.Vector3(0, 1, 0);  // three's cylinders are built along +y
// The camera looks from the front right and above, along -VIEW_FROM.
const VIEW_FROM = new THREE.Vector3(0.55, -0.75, 0.37).normalize();
// The framed box's corners lie within this fraction of the canvas's half-width and
// half-height from its middle: a margin of a tenth of the canvas on each side.
const FRAME_FILL = 0.8;
// The sphere a robot on a fixed base swings in may reach this fraction of the canvas's
// half-sizes: a little past its edges, since an arm reaches that sphere only where it is
// stretched out, rarely across the view.
const SWING_FILL = 1.15;
// A robot smaller than this across (m) is framed as a box this large around its middle.
const MIN_FRAMED = 0.1;
// The loop joints' colour: a ring at frame a's origin facing the camera, a dot at frame
// b's origin and a line between them (that shows while the loop is open).
export const LOOP_COLOR = '#00a3c4';

// Checked up front: three logs a console error when it cannot get a context, and a
// machine without WebGL should get a message in the view instead.
function webglAvailable() {
  const canvas = document.createElement('canvas');
  return Boolean(canvas.getContext('webgl2'));
}

// Pose of a link as a THREE.Matrix4 from {position:[3], rotation:[9 row-major]}.
export const poseMatrix = placementMatrix;

export class ChainView {
  constructor(container) {
    this.container = container;
    this.enabled = webglAvailable();
    if (!this.enabled) {
      const note = document.createElement('p');
      note.className = 'view-message';
      note.textContent = 'This browser has no WebGL 2: the 3D view is off; the simulation and its numbers still run.';
      container.append(note);
      return;
    }
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    container.append(this.renderer.domElement);

    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color('#fbfcfd');
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.01, 200);
    this.camera.up.set(0, 0, 1);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.enableDamping = true;
    // Once the user turns or zooms, meshes arriving later do not move the camera again.
    this.controls.addEventListener('start', () => (this.userMoved = true));
    this.generation = 0;

    this.scene.add(new THREE.HemisphereLight('#ffffff', '#8090a0', 2.2));
    const sun = new THREE.DirectionalLight('#ffffff', 1.6);
    sun.position.set(2, -3, 5);
    this.scene.add(sun);

    this.grid = new THREE.GridHelper(4, 40, '#b8c0cc', '#e3e7ed');
    this.grid.rotation.x = Math.PI / 2;  // GridHelper lies in xz; URDF's floor is xy
    this.scene.add(this.grid);

    this.robotGroup = new THREE.Group();
    this.scene.add(this.robotGroup);
    this.glyphs = null;  // made with the first robot: the directions are the module's (settings.js)
    this.pushLine = new THREE.Line(
      new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(), new THREE.Vector3()]),
      new THREE.LineBasicMaterial({ color: '#d9443a' }),
    );
    this.pushLine.visible = false;
    this.scene.add(this.pushLine);
    // Outside robotGroup: picking and framing see the robot alone.
    this.loopGroup = new THREE.Group();
    this.scene.add(this.loopGroup);
    this.loopMarks = [];
    this.loopNames = '';

    this.raycaster = new THREE.Raycaster();
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  resize() {
    const w = this.container.clientWidth;
    const h = this.container.clientHeight;
    if (!w || !h) return;
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
  }

  // Builds the robot. links: FK output at the initial pose (root first); movable[i]:
  // whether link i hangs on a movable joint; parents[i]: the index of the link link i
  // hangs from (-1 for the root; a chain's are i - 1); look: null, or {frames} of
  // linkVisuals() (web/link_visuals.js: the module's robot.links) and files (where meshes
  // are read from, web/mesh_files.js). Frames the camera on the robot.
  // Returns a promise of the meshes' outcomes ([{filename, link, status, message}]; null
  // when another robot was set before they were all read).
  setChain(links, movable, parents, look = null) {
    if (!this.enabled) return Promise.resolve([]);
    const generation = ++this.generation;
    this.userMoved = false;
    this.floating = Boolean(movable[0]);  // the root moves: a floating base
    if (!this.glyphs) {
      this.glyphs = this.makeGlyphs();
      this.scene.add(this.glyphs.group);
    }
    for (const child of [...this.robotGroup.children]) {
      child.traverse((o) => {
        o.geometry?.dispose();
        for (const m of [o.material ?? []].flat()) m.dispose();
      });
      this.robotGroup.remove(child);
    }
    const origins = links.map((l) => new THREE.Vector3(...l.position));
    // The longest path of segments from the root (a chain's: all of it) sizes the sticks.
    const path = origins.map(() => 0);
    let reach = 0;
    for (let i = 1; i < origins.length; i++) {
      if (parents[i] < 0) continue;
      path[i] = path[parents[i]] + origins[i].distanceTo(origins[parents[i]]);
      reach = Math.max(reach, path[i]);
    }
    reach = Math.max(reach, 0.2);
    const radius = Math.min(0.06, Math.max(0.004, reach * 0.022));
    this.radius = radius;
    const hasVisuals = Boolean(look?.frames.length);

    const linkMaterials = [
      new THREE.MeshStandardMaterial({ color: '#9aa7b8', roughness: 0.55, metalness: 0.1 }),
      new THREE.MeshStandardMaterial({ color: '#e8a33d', roughness: 0.5, metalness: 0.1 }),
    ];
    const jointMaterial = new THREE.MeshStandardMaterial({ color: '#3c4658', roughness: 0.4 });
    const cylinder = new THREE.CylinderGeometry(radius, radius, 1, 20);
    const sphere = new THREE.SphereGeometry(radius * 1.45, 20, 14);

    // A segment runs from a link's origin to each child's: it is the parent link's body,
    // so a push on it acts on that link. The root's segments are the base (fixed, or the
    // floating trunk). With visuals, a segment shows only for a link whose mesh is missing.
    this.parents = parents;
    this.segments = [];
    for (let c = 1; c < links.length; c++) {
      const p = parents[c];
      if (p < 0) continue;
      const mesh = new THREE.Mesh(cylinder, p === 0 ? jointMaterial : linkMaterials[p % 2]);
      mesh.userData.link = p;
      mesh.userData.child = c;
      mesh.userData.shown = !hasVisuals;
      this.segments.push(mesh);
      this.robotGroup.add(mesh);
    }
    this.joints = [];
    links.forEach((_, i) => {
      if (!movable[i]) return;
      const mesh = new THREE.Mesh(sphere, jointMaterial);
      mesh.userData.link = i;
      mesh.userData.jointOf = i;
      mesh.visible = !hasVisuals;
      this.joints.push(mesh);
      this.robotGroup.add(mesh);
    });
    // A link with no child (a chain's tip, a tree's feet and hands) has no segment after
    // it: a small block stands for it.
    const block = new THREE.BoxGeometry(radius * 2.6, radius * 2.6, radius * 1.6);
    this.leafBlocks = [];
    links.forEach((_, i) => {
      if (i === 0 || parents.includes(i)) return;
      const mesh = new THREE.Mesh(block, linkMaterials[1]);
      mesh.userData.link = i;
      mesh.visible = !hasVisuals;
      this.leafBlocks.push(mesh);
      this.robotGroup.add(mesh);
    });
    this.tipAxes = new THREE.AxesHelper(radius * 7);
    this.tipAxes.matrixAutoUpdate = false;
    this.robotGroup.add(this.tipAxes);

    // The visuals, one group per link that has any, moved to the link's pose each frame.
    this.linkFrames = [];
    const loads = [];
    if (hasVisuals) {
      for (const place of look.frames) {
        const frame = new THREE.Group();
        frame.matrixAutoUpdate = false;
        frame.userData.link = place.fk;
        for (const visual of place.visuals) {
          const { object, load } = visualObject(visual);
          frame.add(object);
          if (load) loads.push({ load, link: place.link, fk: place.fk });
        }
        const offset = place.offset ? placementMatrix(place.offset) : new THREE.Matrix4();
        this.linkFrames.push({ frame, fk: place.fk, offset });
        this.robotGroup.add(frame);
      }
    }

    this.glyphs.group.scale.setScalar(radius * 8);
    this.update(links, {}, null);
    this.frameCamera();
    return this.loadMeshes(loads, look?.files, generation);
  }

  async loadMeshes(loads, files, generation) {
    const outcomes = await Promise.all(loads.map(async ({ load, link, fk }) => ({ ...(await load(files)), link, fk })));
    if (generation !== this.generation) return null;
    for (const o of outcomes) {
      if (o.status === 'loaded') continue;
      for (const mesh of [...this.segments, ...this.leafBlocks]) {
        if (mesh.userData.link !== o.fk) continue;
        if (mesh.userData.child !== undefined) mesh.userData.shown = true;
        else mesh.visible = true;
      }
    }
    // The stick figure standing in for missing meshes is placed before it is framed.
    if (this.lastUpdate) this.update(...this.lastUpdate);
    this.robotGroup.updateMatrixWorld(true);
    if (!this.userMoved) this.frameCamera();
    return outcomes.map(({ fk, ...o }) => o);
  }

  // Aims the camera, from the front right and above (along -VIEW_FROM), at the box around
  // the robot as it stands now (its link origins and what is shown of it: its visuals, or
  // the stick figure), from just as far as puts every corner of that box within
  // FRAME_FILL of the canvas's half-width and half-height: a 0.4 m quadruped and a 1.7 m
  // humanoid fill the view alike. A robot on a fixed base swings about its root: the
  // sphere about the root through the box's farthest corner is framed with it, up to a
  // little past the canvas's edges (SWING_FILL). The robot's box is kept (this.framed).
  frameCamera() {
    this.robotGroup.updateMatrixWorld(true);
    const box = visibleBox(this.robotGroup);
    const point = new THREE.Vector3();
    for (const l of this.lastUpdate?.[0] ?? []) box.expandByPoint(point.fromArray(l.position));
    if (box.isEmpty()) box.setFromCenterAndSize(new THREE.Vector3(), new THREE.Vector3());
    const size = box.getSize(new THREE.Vector3());
    const across = Math.max(size.x, size.y, size.z);
    if (across < MIN_FRAMED) box.expandByScalar((MIN_FRAMED - across) / 2);
    // The camera's axes: right and up on the canvas, VIEW_FROM toward the camera.
    const right = new THREE.Vector3(0, 0, 1).cross(VIEW_FROM).normalize();
    const up = VIEW_FROM.clone().cross(right);
    // Points to frame, each with the fraction of the canvas's half-sizes it may reach.
    const points = [0, 1, 2, 3, 4, 5, 6, 7].map((k) => new THREE.Vector3(k & 1 ? box.max.x : box.min.x,
      k & 2 ? box.max.y : box.min.y, k & 4 ? box.max.z : box.min.z));
    const fills = points.map(() => FRAME_FILL);
    // A fixed base: the robot swings about its root, never farther from it than the box's
    // farthest corner is now; that sphere is framed too (its outline, as the points on it
    // along the camera's axes), up to a little past the canvas's edges, so that a falling
    // arm stays in view.
    const links = this.lastUpdate?.[0];
    if (links && !this.floating) {
      const root = new THREE.Vector3().fromArray(links[0].position);
      const reach = Math.max(...points.map((p) => p.distanceTo(root)));
      for (const axis of [right, up, VIEW_FROM]) {
        for (const sign of [1, -1]) {
          points.push(root.clone().addScaledVector(axis, sign * reach));
          fills.push(SWING_FILL);
        }
      }
    }
    const framing = new THREE.Box3().setFromPoints(points);
    const target = framing.getCenter(new THREE.Vector3());
    const tanY = Math.tan(THREE.MathUtils.degToRad(this.camera.fov / 2));
    const tanX = tanY * this.camera.aspect;
    // A corner at (x, y) on the canvas's axes and w toward the camera from the target is
    // inside when |x| <= FRAME_FILL (distance - w) tanX, and likewise for y.
    let distance = 0;
    points.forEach((p, k) => {
      const corner = p.clone().sub(target);
      const w = corner.dot(VIEW_FROM);
      distance = Math.max(distance, w + Math.abs(corner.dot(right)) / (fills[k] * tanX),
        w + Math.abs(corner.dot(up)) / (fills[k] * tanY));
    });
    this.controls.target.copy(target);
    this.camera.position.copy(target).addScaledVector(VIEW_FROM, distance);
    this.camera.near = distance / 100;
    this.camera.far = distance * 50;
    this.camera.updateProjectionMatrix();
    this.controls.update();
    this.camera.updateMatrixWorld();
    this.framed = box;
    // The floor grid (0.1 m squares, scaled with the robot) reaches past the robot.
    const reach = Math.max(...[framing.min, framing.max].flatMap((a) => [framing.min, framing.max].map((b) => Math.hypot(a.x, b.y))));
    this.grid.scale.setScalar(Math.max(1.25 * reach, 0.25) / 2);
  }

  // One glyph group per direction, in a unit frame at the selected link, scaled with the robot.
  makeGlyphs() {
    const group = new THREE.Group();
    const byName = {};
    for (const name of DIRECTIONS) {
      const color = DIRECTION_COLORS[name];
      const material = new THREE.MeshStandardMaterial({ color, roughness: 0.5 });
      const axis = AXES[name];
      const hold = new THREE.Group();
      if (name.startsWith('r')) {
        // A held rotation: a ring around the axis with stops, "no turning about e".
        const ring = new THREE.Mesh(new THREE.TorusGeometry(0.55, 0.045, 10, 40), material);
        ring.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), axis);
        hold.add(ring);
      } else {
        // A held translation: a rail along the axis with a block on it, "no moving along e".
        const rail = new THREE.Mesh(new THREE.CylinderGeometry(0.03, 0.03, 2.2, 10), material);
        rail.quaternion.setFromUnitVectors(UP, axis);
        const stop = new THREE.Mesh(new THREE.BoxGeometry(0.22, 0.22, 0.22), material);
        hold.add(rail, stop);
      }
      // An acceleration setpoint: an arrow along +e or -e.
      const accelerate = new THREE.ArrowHelper(axis, new THREE.Vector3(), 1.2, color, 0.35, 0.2);
      group.add(hold, accelerate);
      byName[name] = { hold, accelerate, axis };
    }
    return { group, byName };
  }

  // Moves the robot to the poses in `links`; directions: name -> mode of the selected
  // link (links index `selected`, default the last: a chain's tip), drawn at `at` (world,
  // where they act; default the link's origin); push: the drag line {from, to} in world
  // coordinates, or null.
  update(links, directions, push, selected = links.length - 1, at = links[selected].position) {
    if (!this.enabled || !this.segments) return;
    this.lastUpdate = [links, directions, push, selected, at];
    const a = new THREE.Vector3();
    const b = new THREE.Vector3();
    this.segments.forEach((mesh) => {
      a.fromArray(links[mesh.userData.link].position);
      b.fromArray(links[mesh.userData.child].position);
      const length = a.distanceTo(b);
      mesh.visible = mesh.userData.shown && length > 1e-6;
      if (!mesh.visible) return;
      mesh.position.copy(a).add(b).multiplyScalar(0.5);
      mesh.quaternion.setFromUnitVectors(UP, b.sub(a).divideScalar(length));
      mesh.scale.set(1, length, 1);
    });
    for (const mesh of this.joints) mesh.position.fromArray(links[mesh.userData.jointOf].position);
    for (const { frame, fk, offset } of this.linkFrames) poseMatrix(links[fk], frame.matrix).multiply(offset);

    for (const mesh of this.leafBlocks) {
      const pose = links[mesh.userData.link];
      mesh.position.fromArray(pose.position);
      mesh.quaternion.setFromRotationMatrix(poseMatrix(pose));
    }
    const tip = links[selected];
    this.tipAxes.matrix.copy(poseMatrix(tip));
    this.glyphs.group.position.fromArray(at);
    for (const name of DIRECTIONS) {
      const glyph = this.glyphs.byName[name];
      const mode = directions[name];
      glyph.hold.visible = mode === 'hold';
      glyph.accelerate.visible = typeof mode === 'number';
      if (typeof mode === 'number') {
        glyph.accelerate.setDirection(mode < 0 ? glyph.axis.clone().negate() : glyph.axis);
      }
    }

    this.pushLine.visible = Boolean(push);
    if (push) {
      this.pushLine.geometry.setFromPoints([push.from, push.to]);
    }
  }

  // Draws each loop joint (ends: [{name, a, b}], its frames' origins in world
  // coordinates, web/simulation.js loopEnds), over the robot so that a pin inside a
  // visual shows; the marks are made again when the loops change.
  updateLoops(ends) {
    if (!this.enabled || !this.segments) return;
    const names = ends.map((e) => e.name).join('\n');
    if (names !== this.loopNames || this.loopRadius !== this.radius) {
      for (const child of [...this.loopGroup.children]) {
        child.traverse((o) => {
          o.geometry?.dispose();
          o.material?.dispose();
        });
        this.loopGroup.remove(child);
      }
      this.loopNames = names;
      this.loopRadius = this.radius;
      const material = () => new THREE.MeshBasicMaterial({ color: LOOP_COLOR, depthTest: false, depthWrite: false,
        transparent: true });
      this.loopMarks = ends.map(() => {
        const ring = new THREE.Mesh(new THREE.TorusGeometry(this.radius * 2.2, this.radius * 0.3, 10, 40), material());
        const dot = new THREE.Mesh(new THREE.SphereGeometry(this.radius * 0.7, 12, 8), material());
        const line = new THREE.Line(new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(), new THREE.Vector3()]),
          new THREE.LineBasicMaterial({ color: LOOP_COLOR, depthTest: false, transparent: true }));
        for (const o of [ring, dot, line]) {
          o.renderOrder = 2;
          this.loopGroup.add(o);
        }
        return { ring, dot, line };
      });
    }
    ends.forEach(({ a, b }, k) => {
      const { ring, dot, line } = this.loopMarks[k];
      ring.position.fromArray(a);
      ring.quaternion.copy(this.camera.quaternion);
      dot.position.fromArray(b);
      line.geometry.setFromPoints([new THREE.Vector3(...a), new THREE.Vector3(...b)]);
    });
  }

  render() {
    if (!this.enabled) return;
    this.controls.update();
    this.renderer.render(this.scene, this.camera);
  }

  ray(clientX, clientY) {
    const rect = this.renderer.domElement.getBoundingClientRect();
    const ndc = new THREE.Vector2(
      ((clientX - rect.left) / rect.width) * 2 - 1,
      -((clientY - rect.top) / rect.height) * 2 + 1,
    );
    this.raycaster.setFromCamera(ndc, this.camera);
    return this.raycaster.ray;
  }

  // The link under the pointer (FK index, root = 0) and the world point hit, or null.
  pick(clientX, clientY) {
    if (!this.enabled || !this.segments) return null;
    this.ray(clientX, clientY);
    for (const hit of this.raycaster.intersectObject(this.robotGroup, true)) {
      if (!hit.object.isMesh || !shown(hit.object)) continue;
      let o = hit.object;
      while (o && o.userData.link === undefined) o = o.parent;
      if (o) return { link: o.userData.link, point: hit.point.clone() };
    }
    return null;
  }

  // Where the pointer's ray meets the plane through `point` facing the camera.
  pointerOnPlane(clientX, clientY, point) {
    const ray = this.ray(clientX, clientY);
    const normal = this.camera.getWorldDirection(new THREE.Vector3());
    const plane = new THREE.Plane().setFromNormalAndCoplanarPoint(normal, point);
    return ray.intersectPlane(plane, new THREE.Vector3());
  }
}

// Whether an object and all its ancestors are visible.
function shown(object) {
  for (let o = object; o; o = o.parent) if (!o.visible) return false;
  return true;
}

// The world box around the visible meshes below `group` (matrices up to date).
function visibleBox(group) {
  const box = new THREE.Box3();
  const part = new THREE.Box3();
  group.traverseVisible((o) => {
    if (!o.isMesh) return;
    o.geometry.computeBoundingBox();
    box.union(part.copy(o.geometry.boundingBox).applyMatrix4(o.matrixWorld));
  });
  return box;
}
