// Meshes of the bodies, one per shape of the scene format (shared/INTERFACE.md):
// sphere radius; box full edge lengths; cylinder and capsule of radius r with their axis
// along the body's z (src/shape.h), the capsule's length being its cylinder part; a mesh
// file's own triangles, which rigidfmu.replay puts in the shape already in the body
// frame (replay/shapes.py), and a compound's parts, each placed in the body frame.
// Each body also gets dark lines fixed in its frame, so that a spinning sphere or a
// cylinder turning about its axis is seen to turn.
import * as THREE from 'three';

const SEGMENTS = 48;

// three.js builds cylinders and capsules along its y axis; the scene's are along z.
function alongZ(geometry) {
  geometry.rotateX(Math.PI / 2);
  return geometry;
}

// A closed polyline in the body frame from [x, y, z] points.
function loop(points, material) {
  const geometry = new THREE.BufferGeometry().setFromPoints(points.map(p => new THREE.Vector3(...p)));
  return new THREE.LineLoop(geometry, material);
}

function circle(radius, plane, offset = 0) {
  const points = [];
  for (let i = 0; i < SEGMENTS; ++i) {
    const a = (2 * Math.PI * i) / SEGMENTS;
    const u = radius * Math.cos(a), v = radius * Math.sin(a);
    points.push(plane === 'xy' ? [u, v, offset] : plane === 'xz' ? [u, offset, v] : [offset, u, v]);
  }
  return points;
}

// The outline of a capsule in its xz plane: two half circles joined by straight sides.
function stadium(radius, half) {
  const points = [];
  for (let i = 0; i <= SEGMENTS / 2; ++i) {
    const a = (Math.PI * i) / (SEGMENTS / 2);
    points.push([radius * Math.cos(a), 0, half + radius * Math.sin(a)]);
  }
  for (let i = 0; i <= SEGMENTS / 2; ++i) {
    const a = Math.PI + (Math.PI * i) / (SEGMENTS / 2);
    points.push([radius * Math.cos(a), 0, -half + radius * Math.sin(a)]);
  }
  return points;
}

function segments(pairs, material) {
  const geometry = new THREE.BufferGeometry().setFromPoints(pairs.flat().map(p => new THREE.Vector3(...p)));
  return new THREE.LineSegments(geometry, material);
}

// A mesh file's triangles as they are (not their hull, which is what collides), shaded
// flat: CAD parts are faceted, and the vertices are shared across sharp edges, where
// averaged normals would round the shading. The lines are its edges sharper than 30°.
function meshParts(shape, material, lines) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.Float32BufferAttribute(shape.vertices, 3));
  geometry.setIndex(shape.triangles);
  const faceted = material.clone();
  faceted.flatShading = true;
  return [new THREE.Mesh(geometry, faceted), new THREE.LineSegments(new THREE.EdgesGeometry(geometry, 30), lines)];
}

// A compound's parts, each a group at its position and orientation in the body frame.
function compoundParts(shape, material, lines) {
  return shape.parts.map(part => {
    const group = new THREE.Group();
    for (const object of parts(part.shape, material, lines)) group.add(object);
    group.position.set(...(part.position ?? [0, 0, 0]));
    const [w, x, y, z] = part.orientation ?? [1, 0, 0, 0];
    group.quaternion.set(x, y, z, w).normalize();
    return group;
  });
}

// The solid and the marker lines of one shape, in the body frame.
function parts(shape, material, lines) {
  // lines drawn a hair outside the surface so that the solid does not hide them
  const out = 1.004;
  switch (shape.type) {
    case 'sphere': {
      const r = shape.radius;
      return [new THREE.Mesh(new THREE.SphereGeometry(r, SEGMENTS, SEGMENTS / 2), material),
              loop(circle(r * out, 'xy'), lines), loop(circle(r * out, 'xz'), lines)];
    }
    case 'box': {
      const geometry = new THREE.BoxGeometry(...shape.size);
      return [new THREE.Mesh(geometry, material),
              new THREE.LineSegments(new THREE.EdgesGeometry(geometry), lines)];
    }
    case 'cylinder': {
      const r = shape.radius, h = shape.length / 2;
      const geometry = alongZ(new THREE.CylinderGeometry(r, r, shape.length, SEGMENTS));
      return [new THREE.Mesh(geometry, material),
              new THREE.LineSegments(new THREE.EdgesGeometry(geometry, 30), lines),
              segments([[[-r, 0, h * out], [r, 0, h * out]], [[-r, 0, -h * out], [r, 0, -h * out]],
                        [[r * out, 0, -h], [r * out, 0, h]]], lines)];
    }
    case 'capsule': {
      const r = shape.radius, h = shape.length / 2;
      const geometry = alongZ(new THREE.CapsuleGeometry(r, shape.length, SEGMENTS / 4, SEGMENTS));
      return [new THREE.Mesh(geometry, material),
              loop(stadium(r * out, h), lines), loop(circle(r * out, 'xy'), lines)];
    }
    case 'mesh':
      return meshParts(shape, material, lines);
    case 'compound':
      return compoundParts(shape, material, lines);
    default:
      throw new Error(`unknown shape type ${shape.type}`);
  }
}

// A group per body, posed later by setPose.
export function bodyObject(body) {
  const colour = new THREE.Color(body.colour);
  const material = new THREE.MeshStandardMaterial({ color: colour, roughness: 0.6, metalness: 0.0 });
  const lines = new THREE.LineBasicMaterial({ color: colour.clone().multiplyScalar(0.35) });
  const group = new THREE.Group();
  group.name = body.name;
  for (const part of parts(body.shape, material, lines)) group.add(part);
  return group;
}

// The radius of the sphere about the centre of mass that holds the shape, m.
export function boundingRadius(shape) {
  switch (shape.type) {
    case 'sphere': return shape.radius;
    case 'box': return 0.5 * Math.hypot(...shape.size);
    case 'cylinder': return Math.hypot(shape.radius, shape.length / 2);
    case 'capsule': return shape.radius + shape.length / 2;
    case 'mesh': {
      let r2 = 0;
      for (let i = 0; i < shape.vertices.length; i += 3) {
        const [x, y, z] = shape.vertices.slice(i, i + 3);
        r2 = Math.max(r2, x * x + y * y + z * z);
      }
      return Math.sqrt(r2);
    }
    // a part turned about its own centre stays inside its sphere
    case 'compound':
      return Math.max(...shape.parts.map(p => Math.hypot(...(p.position ?? [0, 0, 0])) + boundingRadius(p.shape)));
    default: throw new Error(`unknown shape type ${shape.type}`);
  }
}

// Frame i of a body: position and quaternion (w, x, y, z, as in the CSV) to the group.
// A body whose pose the CSV does not hold has a single frame, its start pose.
export function setPose(group, body, i) {
  const p = body.position.length > 3 ? 3 * i : 0;
  const q = body.orientation.length > 4 ? 4 * i : 0;
  group.position.set(body.position[p], body.position[p + 1], body.position[p + 2]);
  // three.js's Quaternion takes (x, y, z, w)
  group.quaternion.set(body.orientation[q + 1], body.orientation[q + 2], body.orientation[q + 3],
                       body.orientation[q]).normalize();  // undoes the CSV's rounding
}
