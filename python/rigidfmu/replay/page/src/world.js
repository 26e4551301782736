// The still parts of the scene: static surfaces (boxes given by min and max, turned
// about their centre by their orientation, src/surface.cpp; a driven surface comes as
// a body, bodies.js), media (axis-aligned boxes, drawn see-through), a ground grid
// under everything, and the lights.
import * as THREE from 'three';

const SURFACE_COLOUR = 0x9a9a9a;
// Media are pale and see-through so that bodies inside them stay visible.
const MEDIUM_COLOURS = { water: 0x6fa8dc, air: 0xdddddd, custom: 0x88c0a8 };

function quaternionOf([w, x, y, z]) {
  return new THREE.Quaternion(x, y, z, w).normalize();
}

function boxWithEdges(size, material, edgeColour) {
  const geometry = new THREE.BoxGeometry(...size);
  const mesh = new THREE.Mesh(geometry, material);
  mesh.add(new THREE.LineSegments(new THREE.EdgesGeometry(geometry),
                                  new THREE.LineBasicMaterial({ color: edgeColour })));
  return mesh;
}

export function surfaceObject(surface) {
  const size = surface.max.map((v, i) => v - surface.min[i]);
  const material = new THREE.MeshStandardMaterial({ color: SURFACE_COLOUR, roughness: 0.9 });
  const mesh = boxWithEdges(size, material, 0x555555);
  mesh.name = surface.name;
  mesh.position.set(...surface.min.map((v, i) => 0.5 * (v + surface.max[i])));
  mesh.quaternion.copy(quaternionOf(surface.orientation));
  return mesh;
}

export function mediumObject(medium) {
  const size = medium.max.map((v, i) => v - medium.min[i]);
  const material = new THREE.MeshStandardMaterial({
    color: MEDIUM_COLOURS[medium.type] ?? MEDIUM_COLOURS.custom,
    transparent: true, opacity: 0.25, depthWrite: false, side: THREE.DoubleSide });
  const mesh = boxWithEdges(size, material, 0x7f96a8);  // greyish: no body colour
  mesh.name = medium.name;
  mesh.position.set(...medium.min.map((v, i) => 0.5 * (v + medium.max[i])));
  mesh.renderOrder = 1;  // after the opaque bodies, which show through
  return mesh;
}

// The eight corners of a surface or medium in the world frame.
export function corners(box) {
  const centre = new THREE.Vector3(...box.min.map((v, i) => 0.5 * (v + box.max[i])));
  const half = new THREE.Vector3(...box.max.map((v, i) => 0.5 * (v - box.min[i])));
  const turn = quaternionOf(box.orientation ?? [1, 0, 0, 0]);
  const points = [];
  for (const sx of [-1, 1]) for (const sy of [-1, 1]) for (const sz of [-1, 1]) {
    points.push(new THREE.Vector3(sx * half.x, sy * half.y, sz * half.z).applyQuaternion(turn).add(centre));
  }
  return points;
}

// A grid in the plane normal to `up` through the lowest point of the bounds, with a cell
// of a round length (1, 2 or 5 times a power of ten) near a tenth of the scene's size.
export function groundGrid(bounds, up) {
  const sphere = bounds.getBoundingSphere(new THREE.Sphere());
  const raw = Math.max(sphere.radius / 5, 1e-3);
  const power = 10 ** Math.floor(Math.log10(raw));
  const cell = [1, 2, 5, 10].map(k => k * power).find(c => c >= raw);
  const cells = 2 * Math.ceil((1.2 * sphere.radius) / cell);
  const grid = new THREE.GridHelper(cells * cell, cells, 0x888888, 0xbbbbbb);
  grid.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), up);
  let lowest = Infinity;
  for (const c of boxCorners(bounds)) lowest = Math.min(lowest, c.dot(up));
  grid.position.copy(sphere.center).addScaledVector(up, lowest - sphere.center.dot(up));
  grid.name = `grid (cell ${cell} m)`;
  return grid;
}

// The eight corners of a THREE.Box3.
export function boxCorners(box) {
  const points = [];
  for (const x of [box.min.x, box.max.x]) for (const y of [box.min.y, box.max.y])
    for (const z of [box.min.z, box.max.z]) points.push(new THREE.Vector3(x, y, z));
  return points;
}

export function addLights(scene, up) {
  const hemisphere = new THREE.HemisphereLight(0xffffff, 0x707070, 2.2);
  hemisphere.position.copy(up);
  scene.add(hemisphere);
  const sun = new THREE.DirectionalLight(0xffffff, 1.6);
  // from above, in front and to the side, so that the faces of a box differ in shade
  const side = Math.abs(up.z) < 0.9 ? new THREE.Vector3(0, 0, 1) : new THREE.Vector3(1, 0, 0);
  const across = new THREE.Vector3().crossVectors(up, side);
  sun.position.copy(up).multiplyScalar(2).add(side).addScaledVector(across, -1.5);
  scene.add(sun);
}
