// Pushing the robot: pressing on a link grabs a point on it, and while the pointer is
// held a spring pulls that point toward the pointer (in the plane facing the camera).
// The spring force becomes a wrench on the link, about its origin and oriented like the
// base (the f_ext convention); the simulator applies it on every step until release.
import * as THREE from 'three';
import { poseMatrix } from './chain_view.js';

export class PushDrag {
  // view: ChainView; hooks.canPush(link) says whether a press on `link` (FK index, root
  // = 0) starts a push; hooks.stiffness() gives the spring constant in N/m.
  constructor(view, hooks) {
    this.view = view;
    this.hooks = hooks;
    this.grab = null;
    if (!view.enabled) return;
    const element = view.renderer.domElement;
    // Capture phase on the container runs before OrbitControls' own listener on the
    // canvas, so a press on a link pushes instead of orbiting.
    view.container.addEventListener('pointerdown', (e) => this.down(e), { capture: true });
    element.addEventListener('pointermove', (e) => this.move(e));
    element.addEventListener('pointerup', () => this.release());
    element.addEventListener('pointercancel', () => this.release());
  }

  down(event) {
    if (event.button !== 0) return;
    const hit = this.view.pick(event.clientX, event.clientY);
    if (!hit || !this.hooks.canPush(hit.link)) return;
    event.stopPropagation();
    event.preventDefault();
    this.view.renderer.domElement.setPointerCapture(event.pointerId);
    const inverse = poseMatrix(this.hooks.linkPose(hit.link)).invert();
    this.grab = { link: hit.link, local: hit.point.clone().applyMatrix4(inverse), target: hit.point.clone() };
  }

  move(event) {
    if (!this.grab) return;
    const to = this.view.pointerOnPlane(event.clientX, event.clientY, this.grabPoint());
    if (to) this.grab.target.copy(to);
  }

  release() {
    this.grab = null;
  }

  grabPoint() {
    return this.grab.local.clone().applyMatrix4(poseMatrix(this.hooks.linkPose(this.grab.link)));
  }

  // The wrench for the current poses (the spring force capped at hooks.maxForce(), so
  // that a long drag cannot fling the robot), {link, wrench: [fx,fy,fz,tx,ty,tz], from, to}, or
  // null when nothing is grabbed.
  current() {
    if (!this.grab) return null;
    const from = this.grabPoint();
    const force = this.grab.target.clone().sub(from).multiplyScalar(this.hooks.stiffness());
    force.clampLength(0, this.hooks.maxForce());
    const origin = new THREE.Vector3().fromArray(this.hooks.linkPose(this.grab.link).position);
    const torque = from.clone().sub(origin).cross(force);
    return { link: this.grab.link, wrench: [...force.toArray(), ...torque.toArray()], from, to: this.grab.target };
  }
}
