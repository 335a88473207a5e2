// The page of `ctmap serve` (issue 15). It holds no map logic: every change goes to the server's
// JSON API (README, "ctmap serve"), which answers with a certified map or the CLI's message.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const $ = (id) => document.getElementById(id);
const SIZE = 480;

// ---- the server -----------------------------------------------------------------------------
let inFlight = 0;
async function api(method, path, body) {
  inFlight++;
  try {
    const r = await fetch(path, {
      method,
      headers: method === 'GET' ? {} : { 'Content-Type': 'application/json' },
      body: body === undefined ? (method === 'GET' ? undefined : '{}') : JSON.stringify(body),
    });
    const j = await r.json();
    if (!r.ok) throw new Error(j.error || `HTTP ${r.status}`);
    return j;
  } finally {
    inFlight--;
  }
}

function status(text, ok) {
  $('status').textContent = text;
  $('status').className = ok ? 'ok' : 'error';
}

// ---- state ----------------------------------------------------------------------------------
let W = 1, H = 1, inputVertices = 0;
let features = [];        // the server's last valid features: {name, vertex | point, image: [x, y]}
let pending = null;       // a mesh vertex picked, waiting for its image point
let selected = null;      // a feature's name
let map = null;           // the last map answer

// ---- 3D view --------------------------------------------------------------------------------
const renderer = new THREE.WebGLRenderer({ antialias: false, preserveDrawingBuffer: true });
renderer.setPixelRatio(1);
renderer.setSize(SIZE, SIZE);
$('view3d').appendChild(renderer.domElement);
const scene = new THREE.Scene();
const camera = new THREE.PerspectiveCamera(35, 1, 0.01, 100);
const controls = new OrbitControls(camera, renderer.domElement);
controls.addEventListener('change', render);

const photo = new THREE.TextureLoader().load('/api/image', render);
photo.colorSpace = THREE.SRGBColorSpace;
photo.generateMipmaps = false;
photo.minFilter = THREE.LinearFilter;
const checker = (() => {
  const c = document.createElement('canvas');
  c.width = c.height = 1024;  // 64 x 64 squares over the whole image: a face in a photograph gets ~10
  const g = c.getContext('2d');
  for (let i = 0; i < 64; i++)
    for (let j = 0; j < 64; j++) {
      g.fillStyle = (i + j) % 2 ? '#e8e8e8' : '#3060c0';
      g.fillRect(i * 16, j * 16, 16, 16);
    }
  const t = new THREE.CanvasTexture(c);
  t.colorSpace = THREE.SRGBColorSpace;
  return t;
})();
const textured = new THREE.MeshBasicMaterial({ map: photo, side: THREE.DoubleSide });
const plain = new THREE.MeshNormalMaterial({ side: THREE.DoubleSide });
const mesh = new THREE.Mesh(new THREE.BufferGeometry(), plain);
scene.add(mesh);
const marker = new THREE.Mesh(new THREE.SphereGeometry(1, 12, 8), new THREE.MeshBasicMaterial({ color: 0xff00ff }));
marker.visible = false;
scene.add(marker);

function render() { renderer.render(scene, camera); }

function setGeometry(vertices, faces, uv) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(vertices, 3));
  if (uv) g.setAttribute('uv', new THREE.Float32BufferAttribute(uv, 2));
  g.setIndex(faces);
  g.computeBoundingSphere();
  mesh.geometry.dispose();
  mesh.geometry = g;
  mesh.material = uv ? textured : plain;
  textured.map = $('mode').value === 'checker' ? checker : photo;
  render();
}

function fitCamera() {
  const s = mesh.geometry.boundingSphere;
  controls.target.copy(s.center);
  camera.position.copy(s.center).add(new THREE.Vector3(0, 0, s.radius * 3.2));
  camera.near = s.radius / 100;
  camera.far = s.radius * 100;
  camera.updateProjectionMatrix();
  marker.scale.setScalar(s.radius / 60);
  controls.update();
  render();
}

// A click (not a drag) on the mesh picks the nearest corner of the face hit (an input vertex).
let down = null;
renderer.domElement.addEventListener('pointerdown', (e) => { down = [e.offsetX, e.offsetY]; });
renderer.domElement.addEventListener('pointerup', (e) => {
  if (!down || Math.hypot(e.offsetX - down[0], e.offsetY - down[1]) > 4) return;
  const ray = new THREE.Raycaster();
  ray.setFromCamera(new THREE.Vector2(e.offsetX / SIZE * 2 - 1, 1 - e.offsetY / SIZE * 2), camera);
  const hit = ray.intersectObject(mesh)[0];
  if (!hit) return;
  const pos = mesh.geometry.getAttribute('position');
  const corners = [hit.face.a, hit.face.b, hit.face.c].filter((v) => v < inputVertices);
  if (!corners.length) return;
  const p = new THREE.Vector3();
  const d = (v) => p.fromBufferAttribute(pos, v).distanceTo(hit.point);
  const vertex = corners.reduce((a, b) => (d(a) <= d(b) ? a : b));
  pending = { vertex };
  marker.position.fromBufferAttribute(pos, vertex);
  marker.visible = true;
  render();
  status(`vertex ${vertex} picked: now click its point on the image`, true);
});

// ---- the image and its features -------------------------------------------------------------
const img = $('image');
const svg = $('overlay');
const scale = () => img.clientWidth / W;

function toPixels(e) {
  const r = img.getBoundingClientRect();
  return [(e.clientX - r.left) / scale(), (e.clientY - r.top) / scale()];
}

function drawOverlay() {
  svg.setAttribute('width', img.clientWidth);
  svg.setAttribute('height', img.clientHeight);
  svg.innerHTML = '';
  for (const f of features) {
    const c = document.createElementNS('http://www.w3.org/2000/svg', 'circle');
    c.setAttribute('cx', f.image[0] * scale());
    c.setAttribute('cy', f.image[1] * scale());
    c.setAttribute('r', 5);
    c.setAttribute('class', 'feature' + (f.name === selected ? ' selected' : ''));
    c.dataset.name = f.name;
    const t = document.createElementNS('http://www.w3.org/2000/svg', 'title');
    t.textContent = f.name;
    c.appendChild(t);
    svg.appendChild(c);
  }
  drawUv();
}

function drawUv() {
  const c = $('uvcanvas');
  c.width = img.clientWidth;
  c.height = img.clientHeight;
  const g = c.getContext('2d');
  g.clearRect(0, 0, c.width, c.height);
  if (!$('showuv').checked || !map) return;
  g.strokeStyle = 'rgba(0, 255, 160, 0.5)';
  g.lineWidth = 0.5;
  g.beginPath();
  const u = map.uv, f = map.faces;
  const x = (v) => u[2 * v] * c.width, y = (v) => (1 - u[2 * v + 1]) * c.height;
  for (let i = 0; i < f.length; i += 3) {
    g.moveTo(x(f[i]), y(f[i]));
    g.lineTo(x(f[i + 1]), y(f[i + 1]));
    g.lineTo(x(f[i + 2]), y(f[i + 2]));
    g.closePath();
  }
  g.stroke();
}

function drawList() {
  const ul = $('features');
  ul.innerHTML = '';
  for (const f of features) {
    const li = document.createElement('li');
    if (f.name === selected) li.className = 'selected';
    const name = document.createElement('input');
    name.value = f.name;
    name.addEventListener('change', () => rename(f.name, name.value));
    const del = document.createElement('button');
    del.textContent = '✕';
    del.title = 'delete';
    del.addEventListener('click', () => remove(f.name));
    li.append(name, ` (${f.vertex !== undefined ? 'v ' + f.vertex : 'point'}) `, del);
    ul.appendChild(li);
  }
}

async function showMap(answer) {
  // A move's answer from the last map leaves out the cut mesh: it is the one of the answer with
  // the same mesh_revision (ours, unless another page re-mapped in between: then the state's).
  if (!answer.faces) {
    let from = map;
    if (!from || from.mesh_revision !== answer.mesh_revision) from = (await api('GET', '/api/state')).map;
    answer.vertices = from.vertices;
    answer.faces = from.faces;
  }
  map = answer;
  setGeometry(answer.vertices, answer.faces, answer.uv);
  const c = answer.certificate;
  $('figures').innerHTML =
    `certificate: <b>${c.valid ? 'valid' : 'INVALID'}</b>, ${c.flipped} flipped, ${c.triangles} triangles<br>` +
    `feature error ${c.feature_max_error}<br>symmetric Dirichlet ${(c.symmetric_dirichlet / 4).toFixed(3)} (1 = isometric)<br>` +
    `map ${answer.timings_ms.total.toFixed(0)} ms`;
}

// Sends a whole features list; on success it becomes the page's.
async function putFeatures(next, what) {
  try {
    await showMap(await api('PUT', '/api/features', { units: 'pixels', features: next }));
    features = next;
    status(what, true);
  } catch (err) {
    status(err.message, false);
  }
  drawOverlay();
  drawList();
}

function rename(old, name) {
  moveChain = moveChain.then(() => putFeatures(features.map((f) => (f.name === old ? { ...f, name } : f)), `renamed ${old} to ${name}`));
}
function remove(name) {
  moveChain = moveChain.then(() => putFeatures(features.filter((f) => f.name !== name), `deleted ${name}`));
}

// Dragging a point: moves are sent while dragging (one at a time, the newest position wins) and
// once more on release; a refused move shows why and the point goes back to the last valid place.
let drag = null;
svg.addEventListener('pointerdown', (e) => {
  const name = e.target.dataset && e.target.dataset.name;
  if (!name) return;
  e.preventDefault();
  svg.setPointerCapture(e.pointerId);
  selected = name;
  drag = { name, at: null, sending: false };
  drawList();
});
svg.addEventListener('pointermove', (e) => {
  if (!drag) return;
  drag.at = toPixels(e);
  const c = [...svg.querySelectorAll('circle')].find((x) => x.dataset.name === drag.name);
  c.setAttribute('cx', drag.at[0] * scale());
  c.setAttribute('cy', drag.at[1] * scale());
  sendMove(false);
});
svg.addEventListener('pointerup', () => {
  if (!drag) return;
  const d = drag;
  drag = null;
  if (d.at) sendMove(true, d);
  else drawOverlay();
});

let moveChain = Promise.resolve();
function sendMove(final, d = drag) {
  if (!final && d.sending) return;
  d.sending = true;
  const at = d.at.slice();
  moveChain = moveChain.then(async () => {
    try {
      await showMap(await api('POST', '/api/move', { name: d.name, image: at }));
      features = features.map((f) => (f.name === d.name ? { ...f, image: at } : f));
      status(`moved ${d.name}`, true);
    } catch (err) {
      status(err.message, false);
    }
    d.sending = false;
    if (final) drawOverlay();
  });
}

// A click on the image (not on a point: the overlay lies over the image) places the picked
// vertex's feature there.
svg.addEventListener('click', (e) => {
  if (!pending || e.target !== svg) return;
  let n = features.length + 1;
  while (features.some((f) => f.name === `feature_${n}`)) n++;
  const f = { name: `feature_${n}`, vertex: pending.vertex, image: toPixels(e) };
  pending = null;
  marker.visible = false;
  selected = f.name;
  moveChain = moveChain.then(() => putFeatures([...features, f], `added ${f.name}`));
});

$('mode').addEventListener('change', () => { textured.map = $('mode').value === 'checker' ? checker : photo; render(); });
$('showuv').addEventListener('change', drawUv);
$('save').addEventListener('click', async () => {
  try {
    const r = await api('POST', '/api/save');
    status(`saved ${r.saved}`, true);
  } catch (err) {
    status(err.message, false);
  }
});

// ---- start ----------------------------------------------------------------------------------
const ready = (async () => {
  const s = await api('GET', '/api/state');
  W = s.image.width;
  H = s.image.height;
  inputVertices = s.mesh.vertices.length / 3;
  features = s.features.features;
  img.src = '/api/image';
  await img.decode();
  if (s.map) await showMap(s.map);
  else setGeometry(s.mesh.vertices, s.mesh.faces, null);
  fitCamera();
  drawOverlay();
  drawList();
  status(s.map ? `${features.length} features, mapped` : 'no features yet', true);
})();

// For the browser test (tests/web/editor_test.mjs): where a mesh vertex is drawn, the drawn
// colour there, the image's colour at a pixel, and whether requests are still running.
window.ctmapEditor = {
  ready,
  idle: () => inFlight === 0,
  features: () => features,
  project(v) {
    const p = new THREE.Vector3().fromBufferAttribute(mesh.geometry.getAttribute('position'), v).project(camera);
    const r = renderer.domElement.getBoundingClientRect();
    return { x: r.left + (p.x + 1) / 2 * SIZE, y: r.top + (1 - p.y) / 2 * SIZE, cx: (p.x + 1) / 2 * SIZE, cy: (1 - p.y) / 2 * SIZE };
  },
  drawnColour(cx, cy) {
    render();
    const gl = renderer.getContext();
    const px = new Uint8Array(4);
    gl.readPixels(Math.round(cx), SIZE - 1 - Math.round(cy), 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
    return [px[0], px[1], px[2]];
  },
  imageColour(x, y) {
    const c = document.createElement('canvas');
    c.width = W;
    c.height = H;
    const g = c.getContext('2d');
    g.drawImage(img, 0, 0);
    const d = g.getImageData(Math.min(W - 1, Math.floor(x)), Math.min(H - 1, Math.floor(y)), 1, 1).data;
    return [d[0], d[1], d[2]];
  },
  imageBox: () => { const r = img.getBoundingClientRect(); return { left: r.left, top: r.top, scale: scale() }; },
};
