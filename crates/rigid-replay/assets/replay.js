// rigid replay: a small WebGL 1 renderer for a recorded multibody trajectory. No library, no
// network: the scene (shapes, meshes, poses at 60 frames per second) is the JSON in #scene.
"use strict";
(function () {
  const scene = JSON.parse(document.getElementById("scene").textContent);
  const canvas = document.getElementById("view");
  const gl = canvas.getContext("webgl", { antialias: true, preserveDrawingBuffer: true });

  function b64(s, Type) {
    const bin = atob(s || "");
    const bytes = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
    return new Type(bytes.buffer);
  }

  // ---- 4x4 column-major matrices ----
  const M = {
    identity() { return [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]; },
    mul(a, b) {
      const o = new Array(16);
      for (let c = 0; c < 4; c++)
        for (let r = 0; r < 4; r++) {
          let s = 0;
          for (let k = 0; k < 4; k++) s += a[k * 4 + r] * b[c * 4 + k];
          o[c * 4 + r] = s;
        }
      return o;
    },
    pose(p, q) { // translation p, unit quaternion q = (x, y, z, w)
      const [x, y, z, w] = q;
      return [1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y), 0,
        2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x), 0,
        2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y), 0,
        p[0], p[1], p[2], 1];
    },
    scale(s) { return [s[0], 0, 0, 0, 0, s[1], 0, 0, 0, 0, s[2], 0, 0, 0, 0, 1]; },
    perspective(fovy, aspect, near, far) {
      const f = 1 / Math.tan(fovy / 2), nf = 1 / (near - far);
      return [f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) * nf, -1, 0, 0, 2 * far * near * nf, 0];
    },
    lookAt(eye, target, up) {
      const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
      const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
      const norm = (a) => { const n = Math.hypot(a[0], a[1], a[2]) || 1; return [a[0] / n, a[1] / n, a[2] / n]; };
      const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
      const f = norm(sub(target, eye)), s = norm(cross(f, up)), u = cross(s, f);
      return [s[0], u[0], -f[0], 0, s[1], u[1], -f[1], 0, s[2], u[2], -f[2], 0,
        -dot(s, eye), -dot(u, eye), dot(f, eye), 1];
    },
  };

  // ---- geometry: triangle lists with flat normals ----
  function flat(pos, idx) { // indexed -> non-indexed with face normals
    const n = idx.length, P = new Float32Array(n * 3), N = new Float32Array(n * 3);
    for (let t = 0; t < n; t += 3) {
      const a = idx[t] * 3, b = idx[t + 1] * 3, c = idx[t + 2] * 3;
      const ux = pos[b] - pos[a], uy = pos[b + 1] - pos[a + 1], uz = pos[b + 2] - pos[a + 2];
      const vx = pos[c] - pos[a], vy = pos[c + 1] - pos[a + 1], vz = pos[c + 2] - pos[a + 2];
      let nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
      const l = Math.hypot(nx, ny, nz) || 1; nx /= l; ny /= l; nz /= l;
      for (let k = 0; k < 3; k++) {
        const i = idx[t + k] * 3, o = (t + k) * 3;
        P[o] = pos[i]; P[o + 1] = pos[i + 1]; P[o + 2] = pos[i + 2];
        N[o] = nx; N[o + 1] = ny; N[o + 2] = nz;
      }
    }
    return { P, N };
  }
  function smooth(P, N) { return { P: new Float32Array(P), N: new Float32Array(N) }; }
  function box() { // unit cube centred at the origin
    const pos = [], idx = [];
    const faces = [[0, 1, 2], [1, 2, 0], [2, 0, 1]];
    for (const [a, b, c] of faces)
      for (const s of [-0.5, 0.5]) {
        const base = pos.length / 3;
        for (const [u, v] of [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]]) {
          const p = [0, 0, 0]; p[a] = s; p[b] = u; p[c] = v; pos.push(...p);
        }
        if (s > 0) idx.push(base, base + 1, base + 2, base, base + 2, base + 3);
        else idx.push(base, base + 2, base + 1, base, base + 3, base + 2);
      }
    return flat(pos, idx);
  }
  // sphere of radius 1, or a capsule (hemispheres at z = ±half) when half > 0
  function sphere(half, seg) {
    const P = [], N = [];
    const rings = seg, slices = 2 * seg;
    const pt = (i, j, off) => {
      const th = Math.PI * i / rings, ph = 2 * Math.PI * j / slices;
      const n = [Math.sin(th) * Math.cos(ph), Math.sin(th) * Math.sin(ph), Math.cos(th)];
      return [n, [n[0], n[1], n[2] + off]];
    };
    const push = ([n, p]) => { P.push(...p); N.push(...n); };
    for (let i = 0; i < rings; i++) {
      const off = i < rings / 2 ? half : -half;
      for (let j = 0; j < slices; j++) {
        const a = pt(i, j, off), b = pt(i + 1, j, off), c = pt(i + 1, j + 1, off), d = pt(i, j + 1, off);
        push(a); push(b); push(c); push(a); push(c); push(d);
        if (half > 0 && i === rings / 2 - 1) { // the cylinder between the caps
          const g = pt(i + 1, j, -half), h = pt(i + 1, j + 1, -half);
          push(b); push(g); push(h); push(b); push(h); push(c);
        }
      }
    }
    return smooth(P, N);
  }
  function cylinder(seg) { // radius 1, z in [-0.5, 0.5]
    const P = [], N = [];
    for (let j = 0; j < seg; j++) {
      const a0 = 2 * Math.PI * j / seg, a1 = 2 * Math.PI * (j + 1) / seg;
      const c0 = Math.cos(a0), s0 = Math.sin(a0), c1 = Math.cos(a1), s1 = Math.sin(a1);
      P.push(c0, s0, -0.5, c1, s1, -0.5, c1, s1, 0.5, c0, s0, -0.5, c1, s1, 0.5, c0, s0, 0.5);
      N.push(c0, s0, 0, c1, s1, 0, c1, s1, 0, c0, s0, 0, c1, s1, 0, c0, s0, 0);
      P.push(0, 0, 0.5, c0, s0, 0.5, c1, s1, 0.5); N.push(0, 0, 1, 0, 0, 1, 0, 0, 1);
      P.push(0, 0, -0.5, c1, s1, -0.5, c0, s0, -0.5); N.push(0, 0, -1, 0, 0, -1, 0, 0, -1);
    }
    return smooth(P, N);
  }
  function cone(seg) { // base radius 1 at z = 0, apex at z = 1
    const P = [], N = [], k = 1 / Math.SQRT2;
    for (let j = 0; j < seg; j++) {
      const a0 = 2 * Math.PI * j / seg, a1 = 2 * Math.PI * (j + 1) / seg;
      const c0 = Math.cos(a0), s0 = Math.sin(a0), c1 = Math.cos(a1), s1 = Math.sin(a1);
      P.push(c0, s0, 0, c1, s1, 0, 0, 0, 1); N.push(c0 * k, s0 * k, k, c1 * k, s1 * k, k, c0 * k, s0 * k, k);
      P.push(0, 0, 0, c1, s1, 0, c0, s0, 0); N.push(0, 0, -1, 0, 0, -1, 0, 0, -1);
    }
    return smooth(P, N);
  }

  // ---- GL ----
  const VS = "attribute vec3 p; attribute vec3 n; uniform mat4 mvp, model; uniform mat3 nm;" +
    "varying vec3 vn; void main(){ vn = normalize(nm * n); gl_Position = mvp * vec4(p, 1.0); }";
  const FS = "precision mediump float; varying vec3 vn; uniform vec4 color; uniform float lit;" +
    "void main(){ vec3 n = normalize(vn); vec3 l1 = normalize(vec3(0.4, 0.3, 1.0)); vec3 l2 = normalize(vec3(-0.6, -0.8, 0.2));" +
    "float d = 0.35 + 0.55 * abs(dot(n, l1)) + 0.2 * max(dot(n, l2), 0.0);" +
    "gl_FragColor = vec4(mix(color.rgb, color.rgb * d, lit), color.a); }";
  function shader(type, src) {
    const s = gl.createShader(type); gl.shaderSource(s, src); gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
    return s;
  }
  let prog = null, loc = {};
  function buffer(data) { const b = gl.createBuffer(); gl.bindBuffer(gl.ARRAY_BUFFER, b); gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW); return b; }
  function upload(g) { return { p: buffer(g.P), n: buffer(g.N), count: g.P.length / 3 }; }

  // ---- the scene ----
  const times = b64(scene.times, Float32Array);
  const nframes = Math.max(1, times.length);
  const nodes = scene.nodes || [];
  const poses = b64(scene.poses, Float32Array);
  const com = scene.com ? b64(scene.com, Float32Array) : null;
  // contact forces: per frame, CONTACT_MARKERS slots of point (m) and force (N); drawn as arrows
  // force_scale metres per newton long
  const forces = scene.forces ? b64(scene.forces, Float32Array) : new Float32Array(0);
  const forceScale = scene.force_scale || 0;
  const SLOTS = scene.force_slots || 16, ARROW_COLOR = [0.1, 0.65, 0.25, 1];
  const geo = {};
  function prepare() {
    prog = gl.createProgram();
    gl.attachShader(prog, shader(gl.VERTEX_SHADER, VS));
    gl.attachShader(prog, shader(gl.FRAGMENT_SHADER, FS));
    gl.linkProgram(prog);
    if (!gl.getProgramParameter(prog, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(prog));
    for (const a of ["p", "n"]) loc[a] = gl.getAttribLocation(prog, a);
    for (const u of ["mvp", "model", "nm", "color", "lit"]) loc[u] = gl.getUniformLocation(prog, u);
    geo.box = upload(box());
    geo.sphere = upload(sphere(0, 12));
    geo.cylinder = upload(cylinder(24));
    geo.cone = upload(cone(16));
    geo.meshes = (scene.meshes || []).map((m) => upload(flat(b64(m.positions, Float32Array), b64(m.indices, Uint32Array))));
    geo.capsules = {};
  }
  function shapeGeometry(s) {
    if (s.kind === "mesh") return [geo.meshes[s.mesh], M.scale(s.scale)];
    if (s.kind === "box") return [geo.box, M.scale(s.size)];
    if (s.kind === "sphere") return [geo.sphere, M.scale([s.size[0], s.size[0], s.size[0]])];
    if (s.kind === "cylinder") return [geo.cylinder, M.scale([s.size[0], s.size[0], s.size[1]])];
    // capsule: radius r, cylinder length l -> a unit-radius capsule with half = l / (2 r)
    const r = s.size[0], half = s.size[1] / (2 * r);
    const key = half.toFixed(3);
    if (!geo.capsules[key]) geo.capsules[key] = upload(sphere(half, 12));
    return [geo.capsules[key], M.scale([r, r, r])];
  }

  // ---- camera: orbit about a target, z up ----
  const cam = { az: -2.2, el: 0.35, dist: 3, target: [0, 0, 0.5] };
  (function fit() {
    let lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    const stride = nodes.length * 7;
    for (let f = 0; f < nframes; f += Math.max(1, Math.floor(nframes / 50)))
      for (let i = 0; i < nodes.length; i++)
        for (let k = 0; k < 3; k++) {
          const x = poses[f * stride + i * 7 + k];
          if (isFinite(x)) { lo[k] = Math.min(lo[k], x); hi[k] = Math.max(hi[k], x); }
        }
    if (!isFinite(lo[0])) { lo = [-0.5, -0.5, 0]; hi = [0.5, 0.5, 1]; }
    const ext = scene.extent || 0.2;
    cam.target = [0, 1, 2].map((k) => (lo[k] + hi[k]) / 2);
    const r = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) / 2 + ext;
    cam.dist = Math.max(0.3, 2.0 * r);
  })();
  function view() {
    const c = Math.cos(cam.el);
    const eye = [cam.target[0] + cam.dist * c * Math.cos(cam.az), cam.target[1] + cam.dist * c * Math.sin(cam.az),
      cam.target[2] + cam.dist * Math.sin(cam.el)];
    return M.lookAt(eye, cam.target, [0, 0, 1]);
  }
  let drag = null;
  canvas.addEventListener("mousedown", (e) => { drag = { x: e.clientX, y: e.clientY, pan: e.button !== 0 || e.shiftKey }; e.preventDefault(); });
  window.addEventListener("mouseup", () => { drag = null; });
  window.addEventListener("mousemove", (e) => {
    if (!drag) return;
    const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    drag.x = e.clientX; drag.y = e.clientY;
    if (drag.pan) {
      const k = cam.dist * 0.0015, s = Math.sin(cam.az), c = Math.cos(cam.az);
      cam.target[0] += k * (dx * s); cam.target[1] -= k * (dx * c); cam.target[2] += k * dy;
    } else {
      cam.az -= dx * 0.008;
      cam.el = Math.max(-1.5, Math.min(1.5, cam.el + dy * 0.008));
    }
    draw();
  });
  canvas.addEventListener("contextmenu", (e) => e.preventDefault());
  canvas.addEventListener("wheel", (e) => { cam.dist *= Math.exp(e.deltaY * 0.001); e.preventDefault(); draw(); }, { passive: false });

  // ---- lines: grid, world frame, trail, body frames ----
  let lineBuf = null;
  function drawLines(mvp, data, color) {
    if (!lineBuf) lineBuf = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, lineBuf);
    gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(data), gl.DYNAMIC_DRAW);
    gl.vertexAttribPointer(loc.p, 3, gl.FLOAT, false, 0, 0);
    gl.disableVertexAttribArray(loc.n);
    gl.vertexAttrib3f(loc.n, 0, 0, 1);
    gl.uniformMatrix4fv(loc.mvp, false, mvp);
    gl.uniform4fv(loc.color, color);
    gl.uniform1f(loc.lit, 0);
    gl.drawArrays(gl.LINES, 0, data.length / 3);
  }
  function grid(size) {
    const d = [], n = 10, s = size / n;
    for (let i = -n; i <= n; i++) { d.push(i * s, -size, 0, i * s, size, 0, -size, i * s, 0, size, i * s, 0); }
    return d;
  }

  // ---- force arrows ----
  // the arrows of frame f: start point, unit direction, length (m)
  function arrows(f) {
    const out = [];
    if (!(forceScale > 0) || forces.length < (f + 1) * SLOTS * 6) return out;
    for (let k = 0; k < SLOTS; k++) {
      const o = (f * SLOTS + k) * 6;
      const F = [forces[o + 3], forces[o + 4], forces[o + 5]], n = Math.hypot(F[0], F[1], F[2]);
      if (!(n > 0)) continue;
      out.push({ at: [forces[o], forces[o + 1], forces[o + 2]], dir: F.map((x) => x / n), length: forceScale * n, force: n });
    }
    return out;
  }
  // a frame whose z axis is d (unit), at p, scaled by (r, r, l)
  function along(p, d, r, l) {
    const h = Math.abs(d[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0];
    let x = [h[1] * d[2] - h[2] * d[1], h[2] * d[0] - h[0] * d[2], h[0] * d[1] - h[1] * d[0]];
    const n = Math.hypot(x[0], x[1], x[2]); x = x.map((v) => v / n);
    const y = [d[1] * x[2] - d[2] * x[1], d[2] * x[0] - d[0] * x[2], d[0] * x[1] - d[1] * x[0]];
    return { M: [x[0] * r, x[1] * r, x[2] * r, 0, y[0] * r, y[1] * r, y[2] * r, 0, d[0] * l, d[1] * l, d[2] * l, 0, p[0], p[1], p[2], 1],
      nm: [x[0], x[1], x[2], y[0], y[1], y[2], d[0], d[1], d[2]] };
  }
  function drawSolid(vp, gm, T) {
    gl.bindBuffer(gl.ARRAY_BUFFER, gm.p); gl.vertexAttribPointer(loc.p, 3, gl.FLOAT, false, 0, 0);
    gl.enableVertexAttribArray(loc.n);
    gl.bindBuffer(gl.ARRAY_BUFFER, gm.n); gl.vertexAttribPointer(loc.n, 3, gl.FLOAT, false, 0, 0);
    gl.uniformMatrix4fv(loc.mvp, false, M.mul(vp, T.M));
    gl.uniformMatrix4fv(loc.model, false, T.M);
    gl.uniformMatrix3fv(loc.nm, false, T.nm);
    gl.uniform4fv(loc.color, ARROW_COLOR);
    gl.uniform1f(loc.lit, 1);
    gl.drawArrays(gl.TRIANGLES, 0, gm.count);
  }
  // shaft and head, over the bodies (no depth test): a force on a foot points into the leg
  function drawArrows(vp) {
    const list = arrows(frame);
    if (!list.length) return;
    gl.disable(gl.DEPTH_TEST);
    const r = Math.max(0.002, 0.006 * (scene.extent || 0.5));
    for (const a of list) {
      const head = Math.min(0.35 * a.length, 4 * r), shaft = a.length - head;
      const mid = a.at.map((x, k) => x + a.dir[k] * shaft / 2);
      const tip = a.at.map((x, k) => x + a.dir[k] * shaft);
      if (shaft > 0) drawSolid(vp, geo.cylinder, along(mid, a.dir, r, shaft));
      drawSolid(vp, geo.cone, along(tip, a.dir, 2.2 * r, head));
    }
    gl.enable(gl.DEPTH_TEST);
  }

  // ---- drawing ----
  let frame = 0;
  function nodePose(f, i) {
    const o = f * nodes.length * 7 + i * 7;
    return M.pose([poses[o], poses[o + 1], poses[o + 2]], [poses[o + 3], poses[o + 4], poses[o + 5], poses[o + 6]]);
  }
  function draw() {
    const w = canvas.clientWidth, h = canvas.clientHeight;
    if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
    gl.viewport(0, 0, canvas.width, canvas.height);
    gl.clearColor(0.956, 0.96, 0.968, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.useProgram(prog);
    const proj = M.perspective(0.8, Math.max(1e-3, w / Math.max(1, h)), cam.dist * 0.01, cam.dist * 100);
    const vp = M.mul(proj, view());
    const g = Math.max(1, Math.ceil(cam.dist));
    drawLines(vp, grid(g), [0.8, 0.81, 0.84, 1]);
    const a = 0.25 * g;
    drawLines(vp, [0, 0, 0, a, 0, 0], [0.85, 0.1, 0.1, 1]);
    drawLines(vp, [0, 0, 0, 0, a, 0], [0.1, 0.65, 0.1, 1]);
    drawLines(vp, [0, 0, 0, 0, 0, a], [0.1, 0.2, 0.9, 1]);
    gl.enableVertexAttribArray(loc.p);
    for (let i = 0; i < nodes.length; i++) {
      const P = nodePose(frame, i);
      for (const s of nodes[i].shapes) {
        const [gm, S] = shapeGeometry(s);
        if (!gm || gm.count === 0) continue;
        const model = M.mul(P, M.mul(s.origin, S));
        gl.bindBuffer(gl.ARRAY_BUFFER, gm.p); gl.vertexAttribPointer(loc.p, 3, gl.FLOAT, false, 0, 0);
        gl.enableVertexAttribArray(loc.n);
        gl.bindBuffer(gl.ARRAY_BUFFER, gm.n); gl.vertexAttribPointer(loc.n, 3, gl.FLOAT, false, 0, 0);
        // normals: the rotation part, non-uniform scale divided out
        const sc = [S[0] || 1, S[5] || 1, S[10] || 1];
        const R = M.mul(P, s.origin);
        const nm = [R[0] / sc[0], R[1] / sc[0], R[2] / sc[0], R[4] / sc[1], R[5] / sc[1], R[6] / sc[1], R[8] / sc[2], R[9] / sc[2], R[10] / sc[2]];
        gl.uniformMatrix4fv(loc.mvp, false, M.mul(vp, model));
        gl.uniformMatrix4fv(loc.model, false, model);
        gl.uniformMatrix3fv(loc.nm, false, nm);
        gl.uniform4fv(loc.color, s.color);
        gl.uniform1f(loc.lit, 1);
        gl.drawArrays(gl.TRIANGLES, 0, gm.count);
      }
    }
    drawArrows(vp);
    if (document.getElementById("frames").checked) {
      const d = [];
      for (let i = 0; i < nodes.length; i++) {
        const P = nodePose(frame, i), l = 0.08 * g;
        for (let k = 0; k < 3; k++) d.push(P[12], P[13], P[14], P[12] + l * P[4 * k], P[13] + l * P[4 * k + 1], P[14] + l * P[4 * k + 2]);
      }
      gl.disable(gl.DEPTH_TEST);
      drawLines(vp, d, [0.2, 0.2, 0.2, 1]);
      gl.enable(gl.DEPTH_TEST);
    }
    if (com && document.getElementById("trail").checked && frame > 0) {
      const d = [];
      for (let f = 1; f <= frame; f++) d.push(com[3 * f - 3], com[3 * f - 2], com[3 * f - 1], com[3 * f], com[3 * f + 1], com[3 * f + 2]);
      drawLines(vp, d, [0.9, 0.45, 0.0, 1]);
    }
    document.getElementById("time").textContent = (times[frame] || 0).toFixed(3) + " s";
  }

  // ---- playback ----
  const slider = document.getElementById("slider"), play = document.getElementById("play"), speed = document.getElementById("speed");
  slider.max = String(nframes - 1);
  let playing = false, clock = 0, last = 0;
  function setFrame(f) {
    frame = Math.max(0, Math.min(nframes - 1, f | 0));
    slider.value = String(frame);
    draw();
  }
  function tick(now) {
    if (!playing) return;
    const dt = last ? (now - last) / 1000 : 0;
    last = now;
    clock += dt * parseFloat(speed.value);
    const tEnd = times[nframes - 1] || 0;
    if (clock > tEnd) clock = 0;
    let f = frame;
    while (f + 1 < nframes && times[f + 1] <= clock) f++;
    if (times[f] > clock) f = 0;
    while (f + 1 < nframes && times[f + 1] <= clock) f++;
    setFrame(f);
    requestAnimationFrame(tick);
  }
  function toggle() {
    playing = !playing;
    play.innerHTML = playing ? "&#10074;&#10074;" : "&#9654;";
    if (playing) { clock = times[frame] || 0; last = 0; requestAnimationFrame(tick); }
  }
  play.addEventListener("click", toggle);
  window.addEventListener("keydown", (e) => { if (e.code === "Space") { toggle(); e.preventDefault(); } });
  slider.addEventListener("input", () => { setFrame(parseInt(slider.value, 10)); clock = times[frame] || 0; });
  for (const id of ["trail", "frames"]) document.getElementById(id).addEventListener("change", draw);
  window.addEventListener("resize", draw);

  document.getElementById("title").textContent = scene.title || "";
  document.getElementById("info").textContent = scene.info || "";
  document.getElementById("warnings").textContent = (scene.warnings || []).join("\n");
  if (!gl) {
    document.getElementById("warnings").textContent = "This browser has no WebGL: the 3D view cannot be drawn.";
    window.replay = { ready: true, nframes, frame: () => 0, setFrame: () => {} };
    return;
  }
  prepare();
  setFrame(0);
  if (nframes > 1 && !/[?&#]paused/.test(location.href)) toggle();
  // for scripted checks (tests): the current frame and a setter
  // screen position (CSS pixels) of node i's origin at the current frame
  function screen(i) {
    const P = nodePose(frame, i);
    const w = canvas.clientWidth, h = canvas.clientHeight;
    const proj = M.perspective(0.8, Math.max(1e-3, w / Math.max(1, h)), cam.dist * 0.01, cam.dist * 100);
    const c = M.mul(M.mul(proj, view()), [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, P[12], P[13], P[14], 1]);
    return [(c[12] / c[15] + 1) * w / 2, (1 - c[13] / c[15]) * h / 2];
  }
  window.replay = { ready: true, nframes, nodes: nodes.length, frame: () => frame, setFrame, screen,
    arrows: () => arrows(frame),
    pause: () => { if (playing) toggle(); } };
})();
