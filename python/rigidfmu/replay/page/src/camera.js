// The camera: placed once so that everything of the run (surfaces, media and every
// body over its whole path) is in view, then moved only by the user (orbit and zoom),
// never by the replay, so that what moves on the screen is the bodies.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { boxCorners } from './world.js';

// Two unit vectors across `up`, the first as close to world x as can be: the view then
// looks along +y with x to the right when up is z.
function across(up) {
  const x = new THREE.Vector3(1, 0, 0);
  const right = x.addScaledVector(up, -x.dot(up));
  if (right.lengthSq() < 1e-6) right.set(0, 1, 0).addScaledVector(up, -up.y);
  right.normalize();
  return [right, new THREE.Vector3().crossVectors(up, right)];
}

export function fittedCamera(bounds, up, aspect, canvas) {
  const sphere = bounds.getBoundingSphere(new THREE.Sphere());
  const radius = Math.max(sphere.radius, 0.1);
  const fov = 40;
  const camera = new THREE.PerspectiveCamera(fov, aspect, radius / 1000, radius * 100);
  camera.up.copy(up);
  const [right, forward] = across(up);
  // from in front, a little to the left and above
  const direction = new THREE.Vector3().addScaledVector(right, -0.35)
    .addScaledVector(forward, -1).addScaledVector(up, 0.4).normalize();
  // the nearest distance at which every corner of the bounds is inside the view, with
  // a margin of a tenth of the half-angles
  const tanV = 0.9 * Math.tan(THREE.MathUtils.degToRad(fov / 2)), tanH = tanV * aspect;
  // the screen's up and right: up without its part along the view
  const viewUp = up.clone().addScaledVector(direction, -up.dot(direction)).normalize();
  const viewRight = new THREE.Vector3().crossVectors(viewUp, direction);
  let distance = radius / 100;
  for (const corner of boxCorners(bounds)) {
    const r = corner.sub(sphere.center);
    const towards = r.dot(direction);  // how much nearer the camera than the centre
    distance = Math.max(distance, towards + Math.abs(r.dot(viewUp)) / tanV,
                        towards + Math.abs(r.dot(viewRight)) / tanH);
  }
  camera.position.copy(sphere.center).addScaledVector(direction, distance);
  const controls = new OrbitControls(camera, canvas);
  controls.target.copy(sphere.center);
  controls.update();
  return { camera, controls };
}
