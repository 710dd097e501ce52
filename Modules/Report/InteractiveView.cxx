#include "InteractiveView.h"

#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace vimlop
{

namespace
{

/// The viewer, plain WebGL 1 with no library: the report must open offline
/// from its folder, on any machine, years later. The airway is seen from
/// outside with each wall drawn only where its normal (into the air) faces
/// the viewer, so the near wall is cut away from every angle and the path
/// inside shows. After its first picture it counts the pixels it drew and
/// says so in the canvas's data-status attribute (what the browser test reads).
const char* const viewerScript =
  R"JS(// VIMLOP report: the interactive 3-D view (WebGL, no library).
(function () {
  'use strict';
  var canvas = document.getElementById('view3d');
  var statusLine = document.getElementById('view3d-status');
  function status(text) {
    canvas.setAttribute('data-status', text);
    if (statusLine) { statusLine.textContent = text; }
  }
  var scene = window.vimlopScene;
  if (!scene) { status('no scene data (scene-data.js is missing)'); return; }
  var gl = canvas.getContext('webgl', { preserveDrawingBuffer: true }) ||
    canvas.getContext('experimental-webgl', { preserveDrawingBuffer: true });
  if (!gl) { status('this browser has no WebGL: see the picture scene.png'); return; }

  // Geometry: the mesh unindexed (each triangle its own 3 vertices), with
  // each face's normal turned to agree with its vertices' normals (into the air).
  var P = scene.model.positions, N = scene.model.normals, T = scene.model.triangles;
  var triangleCount = T.length / 3;
  var meshPositions = new Float32Array(9 * triangleCount);
  var meshNormals = new Float32Array(9 * triangleCount);
  var faceNormals = new Float32Array(9 * triangleCount);
  for (var f = 0; f < triangleCount; ++f) {
    var a = 3 * T[3 * f], b = 3 * T[3 * f + 1], c = 3 * T[3 * f + 2];
    var ux = P[b] - P[a], uy = P[b + 1] - P[a + 1], uz = P[b + 2] - P[a + 2];
    var vx = P[c] - P[a], vy = P[c + 1] - P[a + 1], vz = P[c + 2] - P[a + 2];
    var nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    var sx = N[a] + N[b] + N[c], sy = N[a + 1] + N[b + 1] + N[c + 1], sz = N[a + 2] + N[b + 2] + N[c + 2];
    if (nx * sx + ny * sy + nz * sz < 0) { nx = -nx; ny = -ny; nz = -nz; }
    var corners = [a, b, c];
    for (var k = 0; k < 3; ++k) {
      var o = 9 * f + 3 * k, v = corners[k];
      for (var d = 0; d < 3; ++d) {
        meshPositions[o + d] = P[v + d];
        meshNormals[o + d] = N[v + d];
      }
      faceNormals[o] = nx; faceNormals[o + 1] = ny; faceNormals[o + 2] = nz;
    }
  }
  function cameraLines(cameras, lengthMm) {
    var path = [], arrows = [];
    cameras.forEach(function (cam) {
      var c = cam.centre, d = cam.direction;
      path.push(c[0], c[1], c[2]);
      arrows.push(c[0], c[1], c[2], c[0] + lengthMm * d[0], c[1] + lengthMm * d[1], c[2] + lengthMm * d[2]);
    });
    return { path: new Float32Array(path), arrows: new Float32Array(arrows) };
  }
  // The region of interest: the points and the cameras (the model is much larger).
  var focus = [0, 0, 0], count = 0, radius = 5;
  var interest = scene.points.slice();
  scene.cameras.forEach(function (cam) { interest.push(cam.centre[0], cam.centre[1], cam.centre[2]); });
  if (interest.length === 0) { interest = P; }
  for (var i = 0; i < interest.length; i += 3) {
    focus[0] += interest[i]; focus[1] += interest[i + 1]; focus[2] += interest[i + 2]; ++count;
  }
  focus = focus.map(function (x) { return x / count; });
  for (i = 0; i < interest.length; i += 3) {
    radius = Math.max(radius, Math.hypot(interest[i] - focus[0], interest[i + 1] - focus[1], interest[i + 2] - focus[2]));
  }
  var registered = cameraLines(scene.cameras, 0.25 * radius);
  var truth = cameraLines(scene.trueCameras, 0.25 * radius);

  // Shaders: lit two-sided surface for the mesh, flat colour for points and lines.
  function shader(type, source) {
    var s = gl.createShader(type);
    gl.shaderSource(s, source);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) { throw new Error(gl.getShaderInfoLog(s)); }
    return s;
  }
  var program = gl.createProgram();
  gl.attachShader(program, shader(gl.VERTEX_SHADER,
    'attribute vec3 position; attribute vec3 normal; attribute vec3 faceNormal;' +
    'uniform mat4 view; uniform mat4 projection; uniform float pointSize;' +
    'varying vec3 vNormal; varying vec3 vFaceNormal; varying vec3 vPosition;' +
    'void main() { vec4 p = view * vec4(position, 1.0); vPosition = p.xyz;' +
    '  vNormal = (view * vec4(normal, 0.0)).xyz; vFaceNormal = (view * vec4(faceNormal, 0.0)).xyz;' +
    '  gl_Position = projection * p; gl_PointSize = pointSize; }'));
  gl.attachShader(program, shader(gl.FRAGMENT_SHADER,
    'precision mediump float; uniform vec3 colour; uniform float lit;' +
    'varying vec3 vNormal; varying vec3 vFaceNormal; varying vec3 vPosition;' +
    'void main() { if (lit > 0.5) {' +
    '    if (dot(vFaceNormal, -vPosition) <= 0.0) { discard; }' +
    '    float light = abs(dot(normalize(vNormal), normalize(-vPosition)));' +
    '    gl_FragColor = vec4(colour * (0.3 + 0.7 * light), 1.0);' +
    '  } else { gl_FragColor = vec4(colour, 1.0); } }'));
  gl.linkProgram(program);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS)) { status('WebGL: ' + gl.getProgramInfoLog(program)); return; }
  gl.useProgram(program);
  var at = {
    position: gl.getAttribLocation(program, 'position'),
    normal: gl.getAttribLocation(program, 'normal'),
    faceNormal: gl.getAttribLocation(program, 'faceNormal')
  };
  var un = {};
  ['view', 'projection', 'pointSize', 'colour', 'lit'].forEach(function (n) { un[n] = gl.getUniformLocation(program, n); });
  function buffer(data) {
    var b = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, b);
    gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW);
    return { buffer: b, count: data.length / 3 };
  }
  function attribute(location, b) {
    if (location < 0) { return; }
    if (!b) { gl.disableVertexAttribArray(location); gl.vertexAttrib3f(location, 0, 0, 1); return; }
    gl.bindBuffer(gl.ARRAY_BUFFER, b.buffer);
    gl.enableVertexAttribArray(location);
    gl.vertexAttribPointer(location, 3, gl.FLOAT, false, 0, 0);
  }
  var mesh = { position: buffer(meshPositions), normal: buffer(meshNormals), face: buffer(faceNormals) };
  var parts = [
    { data: buffer(new Float32Array(scene.points)), mode: gl.POINTS, colour: [0.9, 0.05, 0.05] },
    { data: buffer(registered.path), mode: gl.LINE_STRIP, colour: [1.0, 0.85, 0.1] },
    { data: buffer(registered.arrows), mode: gl.LINES, colour: [1.0, 0.85, 0.1] },
    { data: buffer(truth.path), mode: gl.LINE_STRIP, colour: [0.1, 0.85, 0.95] },
    { data: buffer(truth.arrows), mode: gl.LINES, colour: [0.1, 0.85, 0.95] }
  ];

  // The view: turned about the focus; from the patient's left, superior up (LPS: +x, +z).
  var start = { azimuth: 0, elevation: 0, distance: 6 * radius };
  var view = Object.assign({}, start);
  function lookAt(eye, centre, up) {
    function sub(p, q) { return [p[0] - q[0], p[1] - q[1], p[2] - q[2]]; }
    function cross(p, q) { return [p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]]; }
    function unit(p) { var l = Math.hypot(p[0], p[1], p[2]); return [p[0] / l, p[1] / l, p[2] / l]; }
    function dot(p, q) { return p[0] * q[0] + p[1] * q[1] + p[2] * q[2]; }
    var z = unit(sub(eye, centre)), x = unit(cross(up, z)), y = cross(z, x);
    return [x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0,
      -dot(x, eye), -dot(y, eye), -dot(z, eye), 1];
  }
  function perspective(fovyDeg, aspect, near, far) {
    var f = 1 / Math.tan(fovyDeg * Math.PI / 360);
    return [f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) / (near - far), -1,
      0, 0, 2 * far * near / (near - far), 0];
  }
  var frames = 0;
  function draw() {
    var ca = Math.cos(view.azimuth), sa = Math.sin(view.azimuth);
    var ce = Math.cos(view.elevation), se = Math.sin(view.elevation);
    // Azimuth turns about the superior axis, elevation towards it.
    var direction = [ca * ce, sa * ce, se];
    var eye = [focus[0] + view.distance * direction[0], focus[1] + view.distance * direction[1],
      focus[2] + view.distance * direction[2]];
    var up = [-ca * se, -sa * se, ce];
    gl.viewport(0, 0, canvas.width, canvas.height);
    gl.clearColor(0.12, 0.12, 0.16, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.uniformMatrix4fv(un.view, false, new Float32Array(lookAt(eye, focus, up)));
    gl.uniformMatrix4fv(un.projection, false, new Float32Array(
      perspective(30, canvas.width / canvas.height, 0.02 * view.distance, view.distance + 40 * radius)));
    gl.uniform1f(un.pointSize, 3.0);
    gl.uniform1f(un.lit, 1.0);
    gl.uniform3fv(un.colour, [0.88, 0.74, 0.68]);
    attribute(at.position, mesh.position);
    attribute(at.normal, mesh.normal);
    attribute(at.faceNormal, mesh.face);
    gl.drawArrays(gl.TRIANGLES, 0, mesh.position.count);
    gl.uniform1f(un.lit, 0.0);
    attribute(at.normal, null);
    attribute(at.faceNormal, null);
    parts.forEach(function (part) {
      if (part.data.count === 0) { return; }
      gl.uniform3fv(un.colour, part.colour);
      attribute(at.position, part.data);
      gl.drawArrays(part.mode, 0, part.data.count);
    });
    if (frames++ === 0) {
      // What reached the screen: pixels that are not the background.
      var pixels = new Uint8Array(4 * canvas.width * canvas.height);
      gl.readPixels(0, 0, canvas.width, canvas.height, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
      var drawn = 0, red = 0;
      for (var p = 0; p < pixels.length; p += 4) {
        if (Math.abs(pixels[p] - 31) + Math.abs(pixels[p + 1] - 31) + Math.abs(pixels[p + 2] - 41) > 12) { ++drawn; }
        if (pixels[p] > 180 && pixels[p + 1] < 60 && pixels[p + 2] < 60) { ++red; }
      }
      status('drawn: ' + triangleCount + ' triangles, ' + scene.points.length / 3 + ' points, ' +
        scene.cameras.length + ' cameras; ' + drawn + ' pixels drawn, ' + red + ' of them points');
    }
  }
  var drag = null;
  canvas.addEventListener('mousedown', function (e) { drag = { x: e.clientX, y: e.clientY }; });
  window.addEventListener('mouseup', function () { drag = null; });
  window.addEventListener('mousemove', function (e) {
    if (!drag) { return; }
    view.azimuth -= 0.01 * (e.clientX - drag.x);
    view.elevation = Math.max(-1.5, Math.min(1.5, view.elevation + 0.01 * (e.clientY - drag.y)));
    drag = { x: e.clientX, y: e.clientY };
    draw();
  });
  canvas.addEventListener('wheel', function (e) {
    e.preventDefault();
    view.distance = Math.max(0.2 * radius, Math.min(40 * radius, view.distance * Math.exp(0.001 * e.deltaY)));
    draw();
  }, { passive: false });
  canvas.addEventListener('dblclick', function () { view = Object.assign({}, start); draw(); });
  try { draw(); } catch (error) { status('WebGL: ' + error.message); }
})();
)JS";

void appendNumber(std::string& out, double value, const char* format = "%.2f")
{
  char text[32];
  std::snprintf(text, sizeof text, format, value);
  out += text;
}

void appendVector(std::string& out, const Eigen::Vector3d& v, const char* format = "%.2f")
{
  for (int d = 0; d < 3; ++d)
  {
    if (d)
    {
      out += ',';
    }
    appendNumber(out, v[d], format);
  }
}

std::string camerasJson(const std::vector<CameraPose>& cameras)
{
  std::string out = "[";
  for (const CameraPose& camera : cameras)
  {
    out += out.size() > 1 ? ",{\"centre\":[" : "{\"centre\":[";
    appendVector(out, camera.centre);
    out += "],\"direction\":[";
    appendVector(out, camera.viewDirection(), "%.4f");
    out += "]}";
  }
  return out + "]";
}

void writeFile(const std::string& text, const std::filesystem::path& path)
{
  std::ofstream out(path);
  out << text;
  if (!out)
  {
    throwFileError(path.string(), "cannot write the file");
  }
}

} // namespace

std::string writeInteractiveView(const InteractiveScene& scene, const std::string& folder)
{
  // Positions to 0.01 mm and normals to 1e-3: a sixth of the size of full
  // precision, and finer than a screen shows.
  std::string data =
    "// VIMLOP report: the scene of the interactive 3-D view, CT frame (LPS), mm.\n"
    "window.vimlopScene = {\"frame\":\"CT (LPS)\",\"units\":\"mm\",\n"
    "\"model\":{\"positions\":[";
  const TriangleMesh& model = scene.model;
  for (size_t i = 0; i < model.vertices().size(); ++i)
  {
    data += i ? "," : "";
    appendVector(data, model.vertices()[i]);
  }
  data += "],\n\"normals\":[";
  for (size_t i = 0; i < model.vertexNormals().size(); ++i)
  {
    data += i ? "," : "";
    appendVector(data, model.vertexNormals()[i], "%.3f");
  }
  data += "],\n\"triangles\":[";
  for (size_t f = 0; f < model.faces().size(); ++f)
  {
    const Eigen::Vector3i& face = model.faces()[f];
    data += (f ? "," : "") + std::to_string(face[0]) + "," + std::to_string(face[1]) + "," +
      std::to_string(face[2]);
  }
  data += "]},\n\"points\":[";
  for (size_t i = 0; i < scene.pointsCT.size(); ++i)
  {
    data += i ? "," : "";
    appendVector(data, scene.pointsCT[i]);
  }
  data += "],\n\"cameras\":" + camerasJson(scene.camerasCT) +
    ",\n\"trueCameras\":" + camerasJson(scene.trueCamerasCT) + "};\n";
  const std::filesystem::path dir(folder);
  writeFile(data, dir / "scene-data.js");
  writeFile(viewerScript, dir / "view3d.js");
  return "<p>Drag to turn, wheel to zoom, double-click to reset. The near wall is cut away "
         "from every side; seen from the patient's left at first, superior up.</p>\n"
         "<canvas id=\"view3d\" width=\"800\" height=\"600\" style=\"border:1px solid "
         "#888;max-width:100%\"></canvas>\n<p id=\"view3d-status\" "
         "style=\"color:#666;font-size:0.9em\">the view needs JavaScript and WebGL</p>\n"
         "<script src=\"scene-data.js\"></script>\n<script src=\"view3d.js\"></script>\n";
}

} // namespace vimlop
