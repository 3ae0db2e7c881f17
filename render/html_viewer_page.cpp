#include "html_viewer_page.hpp"

namespace sinew::render_detail {

// The data's arrays are base64 of little-endian Float32 / Uint16 arrays (html_viewer.cpp): per frame, bone
// ends (6 per bone), each wire's number of path points and then all the points (Uint16 steps of pointsStep
// from pointsOrigin), tensions and strains.
// window.sinewErrors and window.sinewViewer are the hooks the browser test drives (docs/rendering.md).
const char* const kViewerPage = R"page(<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>@@TITLE@@</title>
<script>
window.sinewErrors = [];
window.addEventListener('error', function (e) { window.sinewErrors.push(String(e.message)); });
(function () {
  var original = console.error;
  console.error = function () { window.sinewErrors.push(Array.prototype.join.call(arguments, ' ')); original.apply(console, arguments); };
})();
</script>
<style>
body { margin: 0; overflow: hidden; font: 13px 'DejaVu Sans', sans-serif; background: #fff; color: #222; }
#view { position: absolute; left: 0; top: 0; right: 0; bottom: 48px; }
#bar { position: absolute; left: 0; right: 0; bottom: 0; height: 48px; display: flex; align-items: center; gap: 10px;
       padding: 0 12px; background: #f3f3f3; border-top: 1px solid #ccc; }
#scrub { flex: 1; }
#side { position: absolute; top: 10px; right: 10px; width: 250px; background: rgba(255,255,255,0.92); border: 1px solid #ccc; padding: 8px; }
.scale { height: 14px; border: 1px solid #444; margin: 2px 0; }
.ends { display: flex; justify-content: space-between; font-size: 11px; margin-bottom: 6px; }
#info { margin-top: 8px; border-top: 1px solid #ccc; padding-top: 6px; min-height: 32px; }
#title { position: absolute; left: 12px; top: 8px; font-size: 15px; }
</style></head>
<body>
<div id="view"></div><div id="title"></div>
<div id="side">
  <div>tension (N)</div><div class="scale" id="tensionScale"></div>
  <div class="ends"><span>0</span><span id="tensionTop"></span></div>
  <div id="strainBox"><div>ligament strain</div><div class="scale" id="strainScale"></div>
  <div class="ends"><span>0</span><span id="strainTop"></span></div></div>
  <div>wires (click one to pick it)</div><div id="kinds"></div>
  <div id="info">no wire picked</div>
  <canvas id="curve" width="250" height="110"></canvas>
</div>
<div id="bar"><button id="play">pause</button><input id="scrub" type="range" min="0" value="0" step="1">
<span id="time"></span><label>speed <select id="speed"><option>0.1</option><option>0.25</option><option>0.5</option>
<option selected>1</option><option>2</option><option>4</option></select></label></div>
<script>@@THREE@@</script>
<script>@@ORBIT@@</script>
<script type="application/json" id="sinew-data">@@DATA@@</script>
<script>
(function () {
'use strict';
var data = JSON.parse(document.getElementById('sinew-data').textContent);
function decode(text, Type) {
  var raw = atob(text), bytes = new Uint8Array(raw.length);
  for (var i = 0; i < raw.length; ++i) bytes[i] = raw.charCodeAt(i);
  return new Type(bytes.buffer);
}
var bones = decode(data.bones, Float32Array), counts = decode(data.counts, Uint16Array);
// Path points arrive as 16-bit steps from the motion's bounding box corner.
var points = new Float32Array(decode(data.points, Uint16Array));
for (var i = 0; i < points.length; ++i) points[i] = data.pointsOrigin[i % 3] + data.pointsStep * points[i];
var tensions = decode(data.tensions, Float32Array), strains = decode(data.strains, Float32Array);
var F = data.times.length, W = data.wires.length, B = data.boneRadius.length;
// start[f * W + w]: where frame f's wire w begins in points (counted in points).
var start = new Uint32Array(F * W + 1);
for (var i = 0; i < F * W; ++i) start[i + 1] = start[i] + counts[i];
var maxSegments = 1;
for (var f = 0; f < F; ++f) {
  var n = 0;
  for (var w = 0; w < W; ++w) n += Math.max(counts[f * W + w] - 1, 0);
  maxSegments = Math.max(maxSegments, n);
}

function mapColour(map, t) {
  t = Math.min(Math.max(t, 0), 1) * (map.length - 1);
  var k = Math.min(Math.floor(t), map.length - 2), s = t - k;
  return [0, 1, 2].map(function (c) { return map[k][c] + s * (map[k + 1][c] - map[k][c]); });
}
function wireValue(f, w) { return data.wires[w].byStrain ? strains[f * W + w] : tensions[f * W + w]; }
function wireColour(f, w) {
  return data.wires[w].byStrain ? mapColour(data.plasma, strains[f * W + w] / data.maxStrain)
                                : mapColour(data.viridis, tensions[f * W + w] / data.maxTension);
}
function css(c) { return 'rgb(' + c.map(function (v) { return Math.round(255 * v); }).join(',') + ')'; }
function gradient(map) { return 'linear-gradient(to right,' + map.map(css).join(',') + ')'; }

document.getElementById('title').textContent = data.title;
document.getElementById('tensionScale').style.background = gradient(data.viridis);
document.getElementById('tensionTop').textContent = data.maxTension.toPrecision(3);
if (data.maxStrain > 0) {
  document.getElementById('strainScale').style.background = gradient(data.plasma);
  document.getElementById('strainTop').textContent = data.maxStrain.toPrecision(3);
} else {
  document.getElementById('strainBox').style.display = 'none';
}

var view = document.getElementById('view');
var renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: true});
renderer.setPixelRatio(window.devicePixelRatio);
renderer.setClearColor(0xffffff);
view.appendChild(renderer.domElement);
var scene = new THREE.Scene();
scene.add(new THREE.AmbientLight(0xffffff, 0.6));
var camera = new THREE.PerspectiveCamera(30, 1, 0.01, 1000);
var light = new THREE.DirectionalLight(0xffffff, 0.5);
camera.add(light);
scene.add(camera);
var up = new THREE.Vector3().fromArray(data.up), toward = new THREE.Vector3().fromArray(data.toward);
camera.up.copy(up);
var box = new THREE.Box3();
for (var p = start[0]; p < start[W]; ++p) box.expandByPoint(new THREE.Vector3().fromArray(points, 3 * p));
for (var b = 0; b < 2 * B; ++b) box.expandByPoint(new THREE.Vector3().fromArray(bones, 3 * b));
var centre = box.getCenter(new THREE.Vector3()), extent = Math.max(box.getSize(new THREE.Vector3()).length(), 1e-3);
camera.position.copy(centre).addScaledVector(toward, 2 * extent);
var controls = new THREE.OrbitControls(camera, renderer.domElement);
controls.target.copy(centre);
controls.update();

// Bones: a cylinder and two spheres per capsule.
var boneMaterial = new THREE.MeshLambertMaterial({color: 0xe3ded0});
var cylinder = new THREE.CylinderBufferGeometry(1, 1, 1, 16, 1, true), sphere = new THREE.SphereBufferGeometry(1, 16, 12);
var boneMeshes = [];
for (var b = 0; b < B; ++b) {
  var parts = [new THREE.Mesh(cylinder, boneMaterial), new THREE.Mesh(sphere, boneMaterial), new THREE.Mesh(sphere, boneMaterial)];
  parts[1].scale.setScalar(data.boneRadius[b]);
  parts[2].scale.setScalar(data.boneRadius[b]);
  parts.forEach(function (m) { scene.add(m); });
  boneMeshes.push(parts);
}
// Wires: one set of vertex-coloured line segments refilled each frame; segmentWire[k] is segment k's wire.
var positions = new Float32Array(6 * maxSegments), colours = new Float32Array(6 * maxSegments);
var segmentWire = new Int32Array(maxSegments);
var geometry = new THREE.BufferGeometry();
geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
geometry.setAttribute('color', new THREE.BufferAttribute(colours, 3));
var lines = new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({vertexColors: THREE.VertexColors}));
lines.frustumCulled = false;
scene.add(lines);

var kinds = {};
data.wires.forEach(function (wire) { kinds[wire.kind] = (kinds[wire.kind] || 0) + 1; });
var kindShown = {};
Object.keys(kinds).forEach(function (kind) {
  kindShown[kind] = true;
  var label = document.createElement('label');
  label.style.display = 'block';
  var box = document.createElement('input');
  box.type = 'checkbox';
  box.checked = true;
  box.addEventListener('change', function () { kindShown[kind] = box.checked; showFrame(state.frame); });
  label.appendChild(box);
  label.appendChild(document.createTextNode(' ' + kind + ' (' + kinds[kind] + ')'));
  document.getElementById('kinds').appendChild(label);
});

var scrub = document.getElementById('scrub'), playButton = document.getElementById('play');
scrub.max = F - 1;
var state = {frame: 0, playing: F > 1, speed: 1, picked: -1, time: data.times[0]};
var yAxis = new THREE.Vector3(0, 1, 0);

function showFrame(f) {
  state.frame = f;
  for (var b = 0; b < B; ++b) {
    var a = new THREE.Vector3().fromArray(bones, 6 * (f * B + b)), c = new THREE.Vector3().fromArray(bones, 6 * (f * B + b) + 3);
    var parts = boneMeshes[b], axis = new THREE.Vector3().subVectors(c, a), length = axis.length(), r = data.boneRadius[b];
    parts[0].visible = length > 0;
    if (length > 0) {
      parts[0].position.addVectors(a, c).multiplyScalar(0.5);
      parts[0].quaternion.setFromUnitVectors(yAxis, axis.divideScalar(length));
      parts[0].scale.set(r, length, r);
    }
    parts[1].position.copy(a);
    parts[2].position.copy(c);
  }
  var k = 0;
  for (var w = 0; w < W; ++w) {
    if (!kindShown[data.wires[w].kind]) continue;
    var colour = state.picked === w ? [0.9, 0.1, 0.1] : wireColour(f, w), s0 = start[f * W + w], n = counts[f * W + w];
    for (var i = 0; i + 1 < n; ++i, ++k) {
      for (var e = 0; e < 2; ++e)
        for (var j = 0; j < 3; ++j) {
          positions[6 * k + 3 * e + j] = points[3 * (s0 + i + e) + j];
          colours[6 * k + 3 * e + j] = colour[j];
        }
      segmentWire[k] = w;
    }
  }
  geometry.setDrawRange(0, 2 * k);
  geometry.attributes.position.needsUpdate = true;
  geometry.attributes.color.needsUpdate = true;
  geometry.computeBoundingSphere();
  scrub.value = f;
  document.getElementById('time').textContent = 't = ' + data.times[f].toFixed(3) + ' s (frame ' + f + ' of ' + F + ')';
  showInfo();
}

function showInfo() {
  var canvas = document.getElementById('curve'), g = canvas.getContext('2d');
  g.clearRect(0, 0, canvas.width, canvas.height);
  var info = document.getElementById('info'), w = state.picked;
  if (w < 0) { info.textContent = 'no wire picked'; return; }
  var wire = data.wires[w], unit = wire.byStrain ? '' : ' N', top = 0;
  info.textContent = wire.name + ' (' + wire.kind + '): ' + (wire.byStrain ? 'strain ' : 'tension ') +
                     wireValue(state.frame, w).toPrecision(4) + unit;
  for (var f = 0; f < F; ++f) top = Math.max(top, wireValue(f, w));
  top = top > 0 ? top : 1;
  var x = function (f) { return 30 + (canvas.width - 36) * (F > 1 ? f / (F - 1) : 0); };
  var y = function (v) { return canvas.height - 14 - (canvas.height - 24) * Math.max(v, 0) / top; };
  g.strokeStyle = '#999'; g.strokeRect(30, 10, canvas.width - 36, canvas.height - 24);
  g.fillStyle = '#222'; g.font = '10px sans-serif';
  g.fillText(top.toPrecision(3), 0, 16); g.fillText('0', 18, canvas.height - 14);
  g.fillText(data.times[0].toFixed(2) + ' s', 30, canvas.height - 2);
  g.fillText(data.times[F - 1].toFixed(2) + ' s', canvas.width - 44, canvas.height - 2);
  g.strokeStyle = '#1f77b4'; g.beginPath();
  for (var f = 0; f < F; ++f) f === 0 ? g.moveTo(x(f), y(wireValue(f, w))) : g.lineTo(x(f), y(wireValue(f, w)));
  g.stroke();
  g.strokeStyle = '#d62728'; g.beginPath(); g.moveTo(x(state.frame), 10); g.lineTo(x(state.frame), canvas.height - 14); g.stroke();
}

function pick(w) { state.picked = w; showFrame(state.frame); }
function setPlaying(playing) { state.playing = playing && F > 1; playButton.textContent = state.playing ? 'pause' : 'play'; }
// The frame at or before motion time t.
function frameAt(t) { var lo = 0, hi = F - 1; while (lo < hi) { var mid = (lo + hi + 1) >> 1; if (data.times[mid] <= t) lo = mid; else hi = mid - 1; } return lo; }

playButton.addEventListener('click', function () { setPlaying(!state.playing); });
scrub.addEventListener('input', function () { setPlaying(false); state.time = data.times[+scrub.value]; showFrame(+scrub.value); });
document.getElementById('speed').addEventListener('change', function (e) { state.speed = +e.target.value; });

var raycaster = new THREE.Raycaster(), downAt = null;
renderer.domElement.addEventListener('pointerdown', function (e) { downAt = [e.clientX, e.clientY]; });
renderer.domElement.addEventListener('pointerup', function (e) {
  if (!downAt || Math.abs(e.clientX - downAt[0]) + Math.abs(e.clientY - downAt[1]) > 4) return;
  var rect = renderer.domElement.getBoundingClientRect();
  var ndc = new THREE.Vector2(2 * (e.clientX - rect.left) / rect.width - 1, 1 - 2 * (e.clientY - rect.top) / rect.height);
  raycaster.setFromCamera(ndc, camera);
  // Within 6 px of the pointer, in world units at the target's distance (Debian's three.js r111 reads
  // linePrecision; later releases params.Line.threshold); of those, the segment nearest the ray.
  var threshold = 6 * 2 * Math.tan(camera.fov * Math.PI / 360) * camera.position.distanceTo(controls.target) / rect.height;
  raycaster.linePrecision = threshold;
  raycaster.params.Line = {threshold: threshold};
  var best = -1, bestDistance = Infinity;
  raycaster.intersectObject(lines).forEach(function (hit) {
    var d = raycaster.ray.distanceToPoint(hit.point);
    if (hit.index < geometry.drawRange.count && d < bestDistance) { bestDistance = d; best = segmentWire[Math.floor(hit.index / 2)]; }
  });
  pick(best);
});

function resize() {
  renderer.setSize(view.clientWidth, view.clientHeight);
  camera.aspect = view.clientWidth / Math.max(view.clientHeight, 1);
  camera.updateProjectionMatrix();
}
window.addEventListener('resize', resize);
resize();
showFrame(0);
setPlaying(state.playing);

var last = null;
function animate(now) {
  requestAnimationFrame(animate);
  if (last !== null && state.playing) {
    state.time += state.speed * (now - last) / 1000;
    if (state.time > data.times[F - 1]) state.time = data.times[0];
    var f = frameAt(state.time);
    if (f !== state.frame) showFrame(f);
  }
  last = now;
  controls.update();
  renderer.render(scene, camera);
}
requestAnimationFrame(animate);

window.sinewViewer = {
  frames: F,
  wireNames: data.wires.map(function (wire) { return wire.name; }),
  getState: function () { return {frame: state.frame, playing: state.playing, speed: state.speed,
                                  picked: state.picked < 0 ? null : data.wires[state.picked].name,
                                  info: document.getElementById('info').textContent}; },
  // Client coordinates (px) of the middle of wire `name`'s path at the frame shown.
  screenPointOfWire: function (name) {
    var w = data.wires.findIndex(function (wire) { return wire.name === name; }), f = state.frame;
    var s0 = start[f * W + w], n = counts[f * W + w], i = Math.floor((n - 1) / 2);
    var p = new THREE.Vector3().fromArray(points, 3 * (s0 + i)).lerp(new THREE.Vector3().fromArray(points, 3 * (s0 + i + 1)), 0.5);
    camera.updateMatrixWorld();
    p.project(camera);
    var rect = renderer.domElement.getBoundingClientRect();
    return {x: rect.left + (p.x + 1) / 2 * rect.width, y: rect.top + (1 - p.y) / 2 * rect.height};
  }
};
})();
</script>
</body></html>
)page";

}  // namespace sinew::render_detail
