// smql view: the memory in three.js, z up, metres. The server (view/server.cpp) answers
// /api/scenes, /api/scene and /api/query; the standalone page (smql export html) carries its scene
// in #smql-scene and has no query box. window.smqlView is the page's state, read by its test.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const state = (window.smqlView = {
  ready: false, scene: null, nodes: 0, hits: [], highlighted: [], route: [], error: null, statement: null,
  mode: '3d', run: null, labels: [], unlabelled: [], colours: {}, things: [], points: 0,
});

const embedded = document.getElementById('smql-scene');
const $ = (id) => document.getElementById(id);
// The API answers only with the token of the address smql view printed (docs/view.md).
const token = new URLSearchParams(window.location.search).get('token') || '';
const api = (path) => fetch(path, { headers: { 'X-Smql-Token': token } });
const container = $('canvas');

// ---- The three.js scene ----------------------------------------------------------------------
// Without WebGL (turned off, or a headless browser without a GPU) three.js cannot draw: the page
// says so where the scene would be, rather than stay blank.
let renderer;
try {
  renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
} catch (e) {
  state.error = 'WebGL is not available in this browser';
  container.innerHTML = '<p class="no-webgl"><b>This browser offers no WebGL, which the view draws the memory ' +
    'with.</b> Turn it on, or in a headless Chromium add --use-angle=swiftshader. Without it, ' +
    '<code>smql map DB</code> draws the floor plan as an image and the shell answers every statement.</p>';
  throw new Error(`${state.error}: ${e.message}`);
}
renderer.setPixelRatio(window.devicePixelRatio);
container.appendChild(renderer.domElement);
const labelLayer = document.createElement('div');
labelLayer.id = 'labels';
container.appendChild(labelLayer);
const world = new THREE.Scene();
world.background = new THREE.Color(0xf4f5f7);
world.add(new THREE.HemisphereLight(0xffffff, 0x8a8f96, 2.2));
const sun = new THREE.DirectionalLight(0xffffff, 1.2);
sun.position.set(3, -4, 8);
world.add(sun);

const perspective = new THREE.PerspectiveCamera(50, 1, 0.05, 500);
perspective.up.set(0, 0, 1);
const plan = new THREE.OrthographicCamera(-1, 1, 1, -1, 0.05, 500);
plan.up.set(0, 1, 0);
let camera = perspective;
let controls = new OrbitControls(camera, renderer.domElement);

const HIGHLIGHT = new THREE.Color(0xff2d55);
const meshes = new Map(); // node id -> mesh
let extras = new THREE.Group(); // hit outlines, the route and its step numbers
world.add(extras);
let bounds = new THREE.Box3();

// Each node comes with its category's colour (model/presentation.cpp: the exports and the map use
// the same); the room's shell is drawn see-through, so that what stands in it shows.
const SHELL_OPACITY = { wall: 0.22, floor: 0.5, ceiling: 0.0, door: 0.55, window: 0.45 };

function style(node) {
  const opacity = SHELL_OPACITY[node.category] ?? (node.kind === 'anchor' ? 0.5 : 0.9);
  return { colour: new THREE.Color(node.colour), opacity };
}

// The capture's points (smql export ply --points): bytes of sRGB made linear, as three.js lights in.
let cloud = null;
const linear = Array.from({ length: 256 }, (_, v) => new THREE.Color().setRGB(v / 255, 0, 0, THREE.SRGBColorSpace).r);
const bytesOf = (base64) => Uint8Array.from(atob(base64), (c) => c.charCodeAt(0));

function buildPoints(points) {
  if (cloud) {
    world.remove(cloud);
    cloud.geometry.dispose();
    cloud = null;
  }
  state.points = points ? points.count : 0;
  $('points').hidden = !points;
  if (!points) return;
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(bytesOf(points.positions).buffer), 3));
  geometry.setAttribute('color', new THREE.BufferAttribute(Float32Array.from(bytesOf(points.colours), (v) => linear[v]), 3));
  cloud = new THREE.Points(geometry, new THREE.PointsMaterial({ size: 0.04, vertexColors: true }));
  cloud.visible = $('points').getAttribute('aria-pressed') === 'true';
  world.add(cloud);
}
$('points').addEventListener('click', () => {
  const shown = $('points').getAttribute('aria-pressed') !== 'true';
  $('points').setAttribute('aria-pressed', String(shown));
  if (cloud) cloud.visible = shown;
});

function build(data) {
  for (const mesh of meshes.values()) world.remove(mesh);
  meshes.clear();
  buildPoints(data.points);
  bounds = new THREE.Box3();
  const legend = new Map();
  state.colours = {};
  for (const node of data.nodes) {
    const { center, size, yaw } = node.box;
    const look = style(node);
    if (look.opacity === 0) continue;
    const material = new THREE.MeshLambertMaterial({
      color: look.colour, transparent: true, opacity: look.opacity, depthWrite: look.opacity > 0.6,
    });
    const mesh = new THREE.Mesh(
      new THREE.BoxGeometry(Math.max(size[0], 0.01), Math.max(size[1], 0.01), Math.max(size[2], 0.01)), material);
    mesh.position.set(center[0], center[1], center[2]);
    mesh.rotation.z = yaw;
    mesh.userData = { node, opacity: look.opacity, colour: look.colour.clone() };
    const edges = new THREE.LineSegments(new THREE.EdgesGeometry(mesh.geometry),
      new THREE.LineBasicMaterial({ color: 0x2b3138, transparent: true, opacity: 0.25 }));
    mesh.add(edges);
    world.add(mesh);
    meshes.set(node.id, mesh);
    bounds.expandByObject(mesh);
    if (!(node.category in SHELL_OPACITY) || node.category === 'door' || node.category === 'window') {
      legend.set(node.category, look.colour.getStyle());
      state.colours[node.category] = node.colour;
    }
  }
  state.things = [...meshes.values()].filter(labelled).map((m) => ({ id: m.userData.node.id, category: m.userData.node.category }));
  labelsDirty = true;
  $('legend').replaceChildren(...[...legend.entries()].sort().map(([category, colour]) => {
    const item = document.createElement('span');
    item.textContent = category;
    item.style.setProperty('--swatch', colour);
    return item;
  }));
  fit();
}

function fit() {
  const centre = bounds.getCenter(new THREE.Vector3());
  const size = bounds.getSize(new THREE.Vector3());
  const radius = Math.max(size.x, size.y, 1) * 0.75;
  const aspect = container.clientWidth / Math.max(container.clientHeight, 1);
  if (camera === perspective) {
    perspective.position.set(centre.x - radius * 0.5, centre.y - radius * 1.3, centre.z + radius * 1.2);
  } else {
    const half = Math.max(size.y / 2, size.x / 2 / aspect) * 1.1;
    Object.assign(plan, { left: -half * aspect, right: half * aspect, top: half, bottom: -half });
    plan.position.set(centre.x, centre.y, bounds.max.z + 10);
    plan.updateProjectionMatrix();
  }
  controls.target.copy(centre);
  controls.update();
}

function resize() {
  const width = container.clientWidth, height = container.clientHeight;
  renderer.setSize(width, height);
  perspective.aspect = width / Math.max(height, 1);
  perspective.updateProjectionMatrix();
  if (camera === plan) fit();
}
// The drawing follows its box: the window, and the legend's height once the scene fills it.
new ResizeObserver(resize).observe(container);

function setMode(mode) {
  state.mode = mode;
  camera = mode === 'plan' ? plan : perspective;
  controls.dispose();
  controls = new OrbitControls(camera, renderer.domElement);
  controls.enableRotate = mode !== 'plan';
  $('plan').setAttribute('aria-pressed', String(mode === 'plan'));
  // From above, the ceiling's fixtures would hide what stands on the floor.
  for (const mesh of meshes.values()) {
    const { kind, box } = mesh.userData.node;
    const bottom = box.center[2] - box.size[2] / 2;
    mesh.visible = mode !== 'plan' || kind === 'anchor' || bottom < bounds.max.z - 0.4;
  }
  labelsDirty = true;
  fit();
}
$('plan').addEventListener('click', () => setMode(state.mode === 'plan' ? '3d' : 'plan'));

// ---- Labels: every thing named where it stands, decluttered as the map's are -----------------
// A label is page text over the drawing, so it reads the same at any zoom. Labels are placed
// highlighted hits first, then larger things before smaller ones, each above, below, right or left
// of the top of its box, wherever it overlaps no label placed before; a thing whose label finds no
// room, or that is out of the picture, is listed in the key under the legend.
let labelsDirty = true;
let lastView = '';
const measure = document.createElement('canvas').getContext('2d');
measure.font = '12px system-ui, sans-serif';
const LABEL_HEIGHT = 18, LABEL_PADDING = 16, LABEL_GAP = 2;  // padding: the CSS's, its bar and a pixel

function labelled(mesh) {
  const { kind, category } = mesh.userData.node;
  return mesh.visible && (kind === 'object' || category === 'door' || category === 'window');
}

function layoutLabels() {
  const width = container.clientWidth, height = container.clientHeight;
  const hit = new Set(state.highlighted);
  const candidates = [...meshes.values()].filter(labelled).sort((a, b) => {
    const ha = hit.has(a.userData.node.id), hb = hit.has(b.userData.node.id);
    if (ha !== hb) return ha ? -1 : 1;
    const [sa, sb] = [a.userData.node.box.size, b.userData.node.box.size];
    return sb[0] * sb[1] * sb[2] - sa[0] * sa[1] * sa[2] || a.userData.node.id - b.userData.node.id;
  });
  const placed = [];
  const unlabelled = [];
  const overlaps = (r) => placed.some((p) => r.left < p.left + p.width + LABEL_GAP && p.left < r.left + r.width + LABEL_GAP &&
    r.top < p.top + p.height + LABEL_GAP && p.top < r.top + r.height + LABEL_GAP);
  for (const mesh of candidates) {
    const { node } = mesh.userData;
    const top = new THREE.Vector3(node.box.center[0], node.box.center[1], node.box.center[2] + node.box.size[2] / 2);
    const p = top.project(camera);
    const x = ((p.x + 1) / 2) * width, y = ((1 - p.y) / 2) * height;
    const w = Math.ceil(measure.measureText(node.category).width) + LABEL_PADDING, h = LABEL_HEIGHT;
    const spots = [[x - w / 2, y - h - 4], [x - w / 2, y + 4], [x + 6, y - h / 2], [x - w - 6, y - h / 2]];
    const spot = p.z < 1 && p.z > -1 && spots.map(([left, top]) => ({ left, top, width: w, height: h }))
      .find((r) => r.left >= 0 && r.top >= 0 && r.left + r.width <= width && r.top + r.height <= height && !overlaps(r));
    if (spot) placed.push({ id: node.id, text: node.category, colour: mesh.userData.colour.getStyle(), ...spot });
    else unlabelled.push(node);
  }
  labelLayer.replaceChildren(...placed.map((l) => {
    const label = document.createElement('span');
    label.className = 'label' + (hit.has(l.id) ? ' hit' : '');
    label.dataset.id = l.id;
    label.textContent = l.text;
    label.style.cssText = `left:${l.left}px;top:${l.top}px;width:${l.width}px;--swatch:${l.colour}`;
    return label;
  }));
  const key = $('key');
  key.hidden = unlabelled.length === 0;
  key.querySelector('summary').textContent =
    `${unlabelled.length} thing${unlabelled.length === 1 ? '' : 's'} not labelled in this view`;
  key.querySelector('div').textContent = unlabelled.map((n) => `${n.category}#${n.id}`)
    .sort((a, b) => a.localeCompare(b, 'en', { numeric: true })).join(', ');
  state.labels = placed;
  state.unlabelled = unlabelled.map((n) => n.id);
}

(function loop() {
  renderer.render(world, camera);
  // Labels follow the camera: laid out again when the view moved or the scene changed.
  const view = camera.matrixWorld.elements.concat(camera.projectionMatrix.elements).join(',');
  if (labelsDirty || view !== lastView) {
    labelsDirty = false;
    lastView = view;
    layoutLabels();
  }
  requestAnimationFrame(loop);
})();

// ---- Hover: a thing's path and description --------------------------------------------------
const raycaster = new THREE.Raycaster();
const pointer = new THREE.Vector2();
renderer.domElement.addEventListener('pointermove', (event) => {
  const rect = renderer.domElement.getBoundingClientRect();
  pointer.set(((event.clientX - rect.left) / rect.width) * 2 - 1, -((event.clientY - rect.top) / rect.height) * 2 + 1);
  raycaster.setFromCamera(pointer, camera);
  const candidates = [...meshes.values()].filter((m) => m.visible && m.userData.node.kind !== 'anchor');
  // Under the pointer, a highlighted hit before what hides it (a cushion sunk in its sofa).
  const under = raycaster.intersectObjects(candidates, false);
  const hit = under.find((h) => state.highlighted.includes(h.object.userData.node.id)) || under[0];
  const tip = $('tooltip');
  if (!hit) {
    tip.hidden = true;
    return;
  }
  const node = hit.object.userData.node;
  const colour = node.attributes && node.attributes.color ? `, ${node.attributes.color}` : '';
  tip.innerHTML = '';
  const title = document.createElement('strong');
  title.textContent = `${node.category}#${node.id}${colour}`;
  const path = document.createElement('div');
  path.textContent = node.path;
  tip.append(title, path);
  if (node.text) {
    const text = document.createElement('div');
    text.className = 'quiet';
    text.textContent = node.text;
    tip.append(text);
  }
  tip.style.left = `${event.clientX + 14}px`;
  tip.style.top = `${event.clientY + 14}px`;
  tip.hidden = false;
});

// ---- Answers: hits highlighted, routes drawn ---------------------------------------------------
function highlight(ids) {
  world.remove(extras);
  extras = new THREE.Group();
  world.add(extras);
  const wanted = new Set(ids);
  state.highlighted = [];
  for (const [id, mesh] of meshes) {
    const { opacity, colour } = mesh.userData;
    const hit = wanted.has(id);
    mesh.material.color.copy(hit ? HIGHLIGHT : colour);
    mesh.material.emissive.copy(hit ? HIGHLIGHT : new THREE.Color(0x000000)).multiplyScalar(hit ? 0.6 : 1);
    mesh.material.opacity = wanted.size === 0 || hit ? (hit ? 1 : opacity) : opacity * 0.3;
    mesh.material.depthWrite = mesh.material.opacity > 0.6;
    if (hit) {
      state.highlighted.push(id);
      extras.add(new THREE.BoxHelper(mesh, HIGHLIGHT));
    }
  }
  labelsDirty = true;
}

function stepLabel(text) {
  const canvas = document.createElement('canvas');
  canvas.width = canvas.height = 64;
  const g = canvas.getContext('2d');
  g.fillStyle = '#1d2329';
  g.beginPath();
  g.arc(32, 32, 28, 0, 2 * Math.PI);
  g.fill();
  g.fillStyle = '#fff';
  g.font = 'bold 30px sans-serif';
  g.textAlign = 'center';
  g.textBaseline = 'middle';
  g.fillText(text, 32, 34);
  const sprite = new THREE.Sprite(new THREE.SpriteMaterial({ map: new THREE.CanvasTexture(canvas), depthTest: false }));
  sprite.scale.set(0.35, 0.35, 1);
  return sprite;
}

function drawRoute(route) {
  state.route = route;
  if (route.length === 0) return;
  const z = bounds.min.z + 0.05;
  const points = route.map((s) => new THREE.Vector3(s.x, s.y, z));
  extras.add(new THREE.Line(new THREE.BufferGeometry().setFromPoints(points),
    new THREE.LineBasicMaterial({ color: 0x0a84ff, linewidth: 3 })));
  route.forEach((s, i) => {
    const label = stepLabel(String(s.step ?? i));
    label.position.set(s.x, s.y, z + 0.3);
    extras.add(label);
  });
}

// A value as the panel prints it: metres and degrees to the centimetre or the hundredth, a box by
// its centre.
function shown(value) {
  if (value === null) return '';
  if (typeof value === 'number') return Number.isInteger(value) ? String(value) : value.toFixed(2);
  if (typeof value === 'object') return `(${value.center.map((x) => x.toFixed(2)).join(', ')})`;
  return String(value);
}

function showAnswer(answer) {
  const panel = $('answer');
  panel.replaceChildren();
  if (answer.error) {
    const error = document.createElement('pre');
    error.className = 'error';
    error.textContent = answer.error.text || answer.error.message;
    panel.append(error);
    return;
  }
  if (answer.message) {
    const message = document.createElement('p');
    message.className = 'message';
    message.textContent = answer.message;
    panel.append(message);
  }
  if (answer.columns && answer.columns.length) {
    const table = document.createElement('table');
    const head = table.insertRow();
    for (const c of answer.columns) head.appendChild(document.createElement('th')).textContent = c;
    for (const row of answer.rows.slice(0, 200)) {
      const tr = table.insertRow();
      for (const c of answer.columns) {
        const v = row[c];
        tr.insertCell().textContent = shown(v);
      }
      if (typeof row.id === 'number') tr.addEventListener('click', () => highlight([row.id]));
    }
    panel.append(table);
    const count = document.createElement('p');
    count.className = 'quiet';
    count.textContent = `${answer.rows.length} row${answer.rows.length === 1 ? '' : 's'}`;
    panel.append(count);
  }
}

async function run(statement) {
  state.statement = statement;
  state.error = null;
  const url = `/api/query?scene=${encodeURIComponent(state.scene)}&q=${encodeURIComponent(statement)}`;
  const answer = await (await api(url)).json();
  state.error = answer.error || null;
  state.hits = answer.hits || [];
  showAnswer(answer);
  highlight(state.hits);
  drawRoute(answer.route || []);
  return answer;
}
state.run = run;
// Where a node's centre is on the page, in CSS pixels (null when it is not drawn).
state.screenOf = (id) => {
  const mesh = meshes.get(id);
  if (!mesh || !mesh.visible) return null;
  const p = mesh.getWorldPosition(new THREE.Vector3()).project(camera);
  const rect = renderer.domElement.getBoundingClientRect();
  return { x: rect.left + ((p.x + 1) / 2) * rect.width, y: rect.top + ((1 - p.y) / 2) * rect.height };
};

$('query').addEventListener('submit', (event) => {
  event.preventDefault();
  const statement = $('statement').value.trim();
  if (statement) run(statement);
});

// ---- Start ----------------------------------------------------------------------------------
async function open(name) {
  const data = embedded ? JSON.parse(embedded.textContent)
    : await (await api(`/api/scene?name=${encodeURIComponent(name)}`)).json();
  if (data.error) throw new Error(data.error.message);
  state.scene = data.name;
  state.nodes = data.nodes.length;
  build(data);
  highlight([]);
  drawRoute([]);
  document.title = `smql view: ${data.name}`;
}

async function start() {
  resize();
  try {
    if (embedded) {
      $('query').hidden = true;
      $('scene').hidden = true;
      await open(null);
    } else {
      const { scenes, current } = await (await api('/api/scenes')).json();
      const select = $('scene');
      for (const name of scenes) select.add(new Option(name, name, false, name === current));
      select.addEventListener('change', () => open(select.value));
      if (scenes.length) await open(current || scenes[0]);
    }
    state.ready = true;
  } catch (error) {
    state.error = { message: String(error) };
    showAnswer({ error: state.error });
  }
}
start();
