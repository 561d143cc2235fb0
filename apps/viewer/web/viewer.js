// The live page of `stillslam run --viewer`: counters, the current frame with
// its features and masks, and the atlas in 3D. Everything comes from the
// server-sent events of /api/events (and /api/state once at load).
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/OrbitControls.js';

const $ = (id) => document.getElementById(id);

// ---- counters ---------------------------------------------------------------
const percent = (v) => (100 * v).toFixed(1) + ' %';
const formats = { mask_coverage: percent, held_coverage: percent, fps: (v) => v.toFixed(1), frame_ms: (v) => v.toFixed(1) };

function showState(s) {
  for (const cell of document.querySelectorAll('#counters td')) {
    const key = cell.id.slice(2);
    if (!(key in s) || s[key] === null) continue;
    cell.textContent = formats[key] ? formats[key](s[key]) : String(s[key]);
  }
  const status = !s.running ? 'ended' : s.paused ? 'paused' : 'running';
  $('run-status').dataset.status = status;
  $('run-status').textContent = status;
  $('btn-pause').disabled = s.paused || !s.running;
  $('btn-resume').disabled = !s.paused || !s.running;
  $('btn-step').disabled = !s.running;
  if (s.pose) viewer3d.showCamera(s.pose, s.map_id);
}

// ---- the frame ----------------------------------------------------------------
const canvas = $('frame-canvas');
const ctx = canvas.getContext('2d');

function drawOverlay(f) {
  ctx.lineWidth = 2;
  for (const inst of f.instances) {
    const colour = inst.dynamic ? '#ff4dff' : '#4dd2ff';
    ctx.strokeStyle = colour;
    const o = inst.outline;
    if (o.length >= 6) {
      ctx.beginPath();
      ctx.moveTo(o[0], o[1]);
      for (let i = 2; i < o.length; i += 2) ctx.lineTo(o[i], o[i + 1]);
      ctx.closePath();
      if (inst.dynamic) {
        ctx.fillStyle = 'rgba(255, 77, 255, 0.25)';
        ctx.fill();
      }
      ctx.stroke();
    } else {
      ctx.strokeRect(inst.box[0], inst.box[1], inst.box[2], inst.box[3]);
    }
    const label = `${inst.class} ${inst.score.toFixed(2)}`;
    ctx.font = '13px sans-serif';
    const w = ctx.measureText(label).width + 6;
    ctx.fillStyle = colour;
    ctx.fillRect(inst.box[0], Math.max(0, inst.box[1] - 16), w, 16);
    ctx.fillStyle = '#000';
    ctx.fillText(label, inst.box[0] + 3, Math.max(12, inst.box[1] - 4));
  }
  for (let i = 0; i < f.kept.length; i += 2) {
    ctx.fillStyle = f.tracked[i / 2] ? '#3ddc84' : '#ffd84d';
    ctx.beginPath();
    ctx.arc(f.kept[i], f.kept[i + 1], 2.2, 0, 2 * Math.PI);
    ctx.fill();
  }
  ctx.strokeStyle = '#ff4d4d';
  ctx.lineWidth = 1.5;
  ctx.beginPath();
  for (let i = 0; i < f.removed.length; i += 2) {
    const x = f.removed[i], y = f.removed[i + 1];
    ctx.moveTo(x - 3, y - 3); ctx.lineTo(x + 3, y + 3);
    ctx.moveTo(x + 3, y - 3); ctx.lineTo(x - 3, y + 3);
  }
  ctx.stroke();
}

function showFrame(f) {
  if (canvas.width !== f.width || canvas.height !== f.height) {
    canvas.width = f.width;
    canvas.height = f.height;
  }
  if (!f.image) {
    ctx.fillStyle = '#000';
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    drawOverlay(f);
    return;
  }
  const img = new Image();
  img.onload = () => { ctx.drawImage(img, 0, 0); drawOverlay(f); canvas.dataset.frame = f.frame; };
  img.src = f.image;
}

// ---- the atlas in 3D --------------------------------------------------------------
function makeViewer3d() {
  const host = $('map-view');
  let renderer;
  try {
    renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  } catch (e) {
    $('map-message').textContent = '3D view unavailable (no WebGL): ' + e.message;
    return { showAtlas() {}, showCamera() {} };
  }
  host.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0x101215);
  const camera = new THREE.PerspectiveCamera(60, 1, 0.01, 1000);
  camera.up.set(0, -1, 0);  // the cameras' y axis points down
  camera.position.set(0, -1.5, -3);
  const controls = new OrbitControls(camera, renderer.domElement);
  const maps = new THREE.Group();
  scene.add(maps);
  const visible = new Map();  // map id -> shown
  let fitted = false;
  let bounds = new THREE.Box3();

  // A camera as a small pyramid, in its own frame (z forward, y down).
  const frustum = (s) => {
    const w = s, h = 0.75 * s, d = 0.8 * s;
    const c = [[-w, -h, d], [w, -h, d], [w, h, d], [-w, h, d]];
    const v = [];
    for (let i = 0; i < 4; ++i) {
      v.push(0, 0, 0, ...c[i]);
      v.push(...c[i], ...c[(i + 1) % 4]);
    }
    return v;
  };
  const poseMatrix = (p) => new THREE.Matrix4().compose(
    new THREE.Vector3(p[0], p[1], p[2]), new THREE.Quaternion(p[3], p[4], p[5], p[6]), new THREE.Vector3(1, 1, 1));

  const current = new THREE.LineSegments(
    new THREE.BufferGeometry().setAttribute('position', new THREE.Float32BufferAttribute(frustum(0.08), 3)),
    new THREE.LineBasicMaterial({ color: 0xff4d4d }));
  current.matrixAutoUpdate = false;
  current.visible = false;
  scene.add(current);

  function resize() {
    const w = host.clientWidth, h = host.clientHeight;
    renderer.setSize(w, h);
    camera.aspect = w / Math.max(1, h);
    camera.updateProjectionMatrix();
  }
  new ResizeObserver(resize).observe(host);
  resize();

  function fit() {
    if (bounds.isEmpty()) return;
    const centre = bounds.getCenter(new THREE.Vector3());
    const size = Math.max(0.5, bounds.getSize(new THREE.Vector3()).length());
    controls.target.copy(centre);
    camera.position.copy(centre).add(new THREE.Vector3(0, -0.6 * size, -0.9 * size));
    controls.update();
  }
  $('btn-fit').onclick = fit;

  function mapList(atlas) {
    const list = $('map-list');
    list.textContent = '';
    for (const m of atlas.maps) {
      if (!visible.has(m.id)) visible.set(m.id, true);
      const label = document.createElement('label');
      const box = document.createElement('input');
      box.type = 'checkbox';
      box.checked = visible.get(m.id);
      box.onchange = () => {
        visible.set(m.id, box.checked);
        for (const g of maps.children) if (g.userData.id === m.id) g.visible = box.checked;
      };
      label.append(box, ` map ${m.id}${m.active ? ' (active)' : ''}: ${m.keyframes.length / 7} keyframes`);
      list.append(label);
    }
  }

  function showAtlas(atlas) {
    for (const g of [...maps.children]) {
      g.traverse((o) => { if (o.geometry) o.geometry.dispose(); if (o.material) o.material.dispose(); });
      maps.remove(g);
    }
    bounds = new THREE.Box3();
    for (const m of atlas.maps) {
      const g = new THREE.Group();
      g.userData.id = m.id;
      g.visible = visible.get(m.id) ?? true;
      const dim = m.active ? 1 : 0.45;
      const points = new THREE.BufferGeometry().setAttribute('position', new THREE.Float32BufferAttribute(m.points, 3));
      points.computeBoundingBox();
      if (m.active && m.points.length) bounds.union(points.boundingBox);
      g.add(new THREE.Points(points, new THREE.PointsMaterial({ size: 2, sizeAttenuation: false, color: new THREE.Color(dim, dim, dim) })));
      const kf = [], centres = [];
      const shape = frustum(0.04);
      for (let i = 0; i < m.keyframes.length; i += 7) {
        const T = poseMatrix(m.keyframes.slice(i, i + 7));
        centres.push(m.keyframes[i], m.keyframes[i + 1], m.keyframes[i + 2]);
        for (let j = 0; j < shape.length; j += 3) {
          const v = new THREE.Vector3(shape[j], shape[j + 1], shape[j + 2]).applyMatrix4(T);
          kf.push(v.x, v.y, v.z);
        }
      }
      g.add(new THREE.LineSegments(new THREE.BufferGeometry().setAttribute('position', new THREE.Float32BufferAttribute(kf, 3)),
        new THREE.LineBasicMaterial({ color: m.active ? 0x4d9dff : 0x39577a })));
      const edges = [];
      for (let i = 0; i < m.covisibility.length; i += 2) {
        const a = 3 * m.covisibility[i], b = 3 * m.covisibility[i + 1];
        edges.push(centres[a], centres[a + 1], centres[a + 2], centres[b], centres[b + 1], centres[b + 2]);
      }
      g.add(new THREE.LineSegments(new THREE.BufferGeometry().setAttribute('position', new THREE.Float32BufferAttribute(edges, 3)),
        new THREE.LineBasicMaterial({ color: 0x3ddc84, transparent: true, opacity: 0.35 })));
      g.add(new THREE.Line(new THREE.BufferGeometry().setAttribute('position', new THREE.Float32BufferAttribute(m.trajectory, 3)),
        new THREE.LineBasicMaterial({ color: m.active ? 0xffb347 : 0x7a5a2e })));
      const gt = atlas.groundtruth;
      if (gt && gt.map === m.id && gt.points.length >= 6) {
        g.add(new THREE.Line(new THREE.BufferGeometry().setAttribute('position', new THREE.Float32BufferAttribute(gt.points, 3)),
          new THREE.LineBasicMaterial({ color: 0x8fd18f, transparent: true, opacity: 0.7 })));
        $('gt-key').hidden = false;
      }
      maps.add(g);
    }
    mapList(atlas);
    if (!fitted && !bounds.isEmpty()) { fit(); fitted = true; }
  }

  function showCamera(pose) {
    current.matrix.copy(poseMatrix(pose));
    current.visible = true;
  }

  renderer.setAnimationLoop(() => { controls.update(); renderer.render(scene, camera); });
  return { showAtlas, showCamera };
}
const viewer3d = makeViewer3d();

// ---- buttons and the event stream ---------------------------------------------------
async function control(action) {
  const res = await fetch('/api/' + action, { method: 'POST' });
  if (res.ok) showState(await res.json());
}
$('btn-pause').onclick = () => control('pause');
$('btn-step').onclick = () => control('step');
$('btn-resume').onclick = () => control('resume');

fetch('/api/state').then((r) => r.json()).then(showState).catch(() => {});
const events = new EventSource('/api/events');
events.addEventListener('state', (e) => showState(JSON.parse(e.data)));
events.addEventListener('frame', (e) => showFrame(JSON.parse(e.data)));
events.addEventListener('map', (e) => { const a = JSON.parse(e.data); if (a) viewer3d.showAtlas(a); });
events.onerror = () => {
  if ($('run-status').dataset.status !== 'ended') {
    $('run-status').dataset.status = 'disconnected';
    $('run-status').textContent = 'disconnected (retrying)';
  }
};
