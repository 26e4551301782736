// The replay page: reads the run embedded by rigidfmu.replay (a JSON block, format in
// that file's docstring), builds the scene once and poses the bodies frame by frame.
import * as THREE from 'three';
import { bodyObject, boundingRadius, setPose } from './bodies.js';
import { fittedCamera } from './camera.js';
import { Playback } from './playback.js';
import { addLights, corners, groundGrid, mediumObject, surfaceObject } from './world.js';

function legend(run) {
  document.title = `${run.title} — rigidfmu replay`;
  document.getElementById('title').textContent = run.title;
  const list = document.getElementById('bodies');
  return run.bodies.map(body => {
    const row = document.createElement('div');
    row.className = 'row';
    const swatch = document.createElement('span');
    swatch.className = 'swatch';
    swatch.style.background = body.colour;
    const name = document.createElement('span');
    // a driven body (a pusher, a moving surface) is moved by its inputs, not by the world
    const kind = body.motion === 'driven' ? `${body.shape.type}, driven` : body.shape.type;
    name.textContent = `${body.name} (${kind})`;
    const contacts = document.createElement('span');
    contacts.className = 'contacts';
    row.append(swatch, name, contacts);
    list.append(row);
    return contacts;
  });
}

// Everything that is ever drawn: still boxes, and every body along its whole path.
function boundsOf(run) {
  const bounds = new THREE.Box3();
  for (const box of [...run.surfaces, ...run.media]) for (const c of corners(box)) bounds.expandByPoint(c);
  for (const body of run.bodies) {
    const r = boundingRadius(body.shape);
    for (let i = 0; i < body.position.length; i += 3) {
      const p = new THREE.Vector3(body.position[i], body.position[i + 1], body.position[i + 2]);
      bounds.expandByPoint(p.clone().addScalar(r)).expandByPoint(p.addScalar(-r));
    }
  }
  return bounds;
}

function main() {
  const run = JSON.parse(document.getElementById('replay-data').textContent);
  const view = document.getElementById('view');
  const renderer = new THREE.WebGLRenderer({ antialias: true });
  renderer.setPixelRatio(window.devicePixelRatio);
  renderer.setSize(view.clientWidth, view.clientHeight);
  view.prepend(renderer.domElement);

  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xe8ecf0);
  const up = new THREE.Vector3(...run.up);
  addLights(scene, up);
  const bounds = boundsOf(run);
  scene.add(groundGrid(bounds, up));
  for (const surface of run.surfaces) scene.add(surfaceObject(surface));
  for (const medium of run.media) scene.add(mediumObject(medium));
  const objects = run.bodies.map(bodyObject);
  for (const object of objects) scene.add(object);
  const contactLabels = legend(run);

  const { camera, controls } = fittedCamera(bounds, up, view.clientWidth / view.clientHeight,
                                            renderer.domElement);
  const render = () => renderer.render(scene, camera);
  const playback = new Playback(run.time, i => {
    run.bodies.forEach((body, k) => {
      setPose(objects[k], body, i);
      contactLabels[k].textContent = body.contacts ? `${body.contacts[i]} contacts` : '';
    });
    render();  // at once, so that a moved slider shows before the next animation frame
  });

  window.addEventListener('resize', () => {
    renderer.setSize(view.clientWidth, view.clientHeight);
    camera.aspect = view.clientWidth / view.clientHeight;
    camera.updateProjectionMatrix();
    render();
  });
  controls.addEventListener('change', render);

  playback.show(0);
  playback.setPlaying(true);
  let last = performance.now();
  renderer.setAnimationLoop(now => {
    playback.advance((now - last) / 1000);
    last = now;
  });
}

try {
  main();
} catch (error) {
  // a page that cannot draw says why, in the page and on the console
  const message = document.createElement('p');
  message.id = 'error';
  message.textContent = `The replay cannot be shown: ${error.message}`;
  document.body.prepend(message);
  console.error(error);
}
