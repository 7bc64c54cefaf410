// PhysLab's replay viewer: reads the replays inlined in the page (base64, layout on the
// conventions page, "Replay files"), draws them with three.js (r111, Debian's libjs-three, inlined
// by tools/view.py) and plays them. One replay, or two side by side (the student's and the
// reference) under one camera. Every failure is written into the page: never a blank page.
(function () {
  "use strict";

  const data = JSON.parse(document.getElementById("physlab-data").textContent);
  const $ = (id) => document.getElementById(id);

  function fail(message) {
    const box = $("error");
    box.textContent = message;
    box.hidden = false;
    for (const id of ["view", "controls", "panel"]) $(id).hidden = true;  // nothing to play
  }

  // ---------------------------------------------------------------- replay decoding
  const MAGIC = "PHYSLAB-REPLAY";
  const VERSION = 3;

  function decodeReplay(base64, what) {
    const raw = atob(base64);
    const bytes = new Uint8Array(raw.length);
    for (let i = 0; i < raw.length; ++i) bytes[i] = raw.charCodeAt(i);
    const view = new DataView(bytes.buffer);
    let at = 0;
    const need = (n, field) => {
      if (bytes.length - at < n) {
        throw new Error(`replay ${what}: truncated at byte ${bytes.length}: ${field} (${n} bytes from byte ${at}) is missing`);
      }
    };
    const u32 = () => { const v = view.getUint32(at, true); at += 4; return v; };
    const f32 = () => { const v = view.getFloat32(at, true); at += 4; return v; };
    const text = (field) => {
      need(4, field); const n = u32(); need(n, field);
      const s = new TextDecoder().decode(bytes.subarray(at, at + n)); at += n; return s;
    };
    if (String.fromCharCode(...bytes.subarray(0, MAGIC.length)) !== MAGIC) {
      throw new Error(`replay ${what}: not a PhysLab replay: bytes 0-13 are not "${MAGIC}"`);
    }
    at = MAGIC.length;
    need(2, "the version");
    const version = view.getUint16(at, true); at += 2;
    if (version < 1 || version > VERSION) throw new Error(`replay ${what}: version ${version} at byte 14 is not one this page knows (1-${VERSION})`);
    need(16, "the header's counts");
    const B = u32(), P = u32(), S = u32(), F = u32();
    const replay = { title: text("the title"), settings: text("the settings"), bodies: [], particles: P, springs: [], frames: [] };
    for (let i = 0; i < B; ++i) {
      need(32, `body ${i}`);
      const body = { kind: u32(), fixed: u32() !== 0, size: [f32(), f32(), f32(), f32()] };
      const V = u32(), K = u32();
      need(12 * (V + K), `body ${i}'s vertices and triangles`);
      body.vertices = Array.from({ length: 3 * V }, f32);
      body.triangles = Array.from({ length: 3 * K }, u32);
      replay.bodies.push(body);
    }
    need(8 * S, `the ${S} springs`);
    replay.springs = Array.from({ length: 2 * S }, u32);
    for (let f = 0; f < F; ++f) {
      need(version > 1 ? 24 : 20, `frame ${f}'s time, energies and counts`);
      const frame = { time: f32(), kinetic: f32(), potential: f32(), iterations: u32() };
      const C = u32();
      // A frame whose contacts were left out (a large scene) shows the last recorded ones
      const flags = version === 1 ? 1 : u32();
      const recorded = (flags & 1) !== 0;
      if (!recorded && C !== 0) throw new Error(`replay ${what}: frame ${f} holds ${C} contacts but says they were not recorded`);
      frame.contactsFrom = recorded ? f : (f > 0 ? replay.frames[f - 1].contactsFrom : null);
      need(28 * B, `frame ${f}'s poses`);
      frame.poses = new Float32Array(bytes.buffer.slice(at, at + 28 * B)); at += 28 * B;
      // Version 3, flag bit 1: a byte per body, 1 while it sleeps (Settings::sleeping)
      frame.asleep = null;
      if (version > 2 && (flags & 2) !== 0) {
        need(B, `frame ${f}'s sleeping bodies`);
        frame.asleep = bytes.slice(at, at + B); at += B;
      }
      need(12 * P, `frame ${f}'s particles`);
      frame.particles = new Float32Array(bytes.buffer.slice(at, at + 12 * P)); at += 12 * P;
      need(40 * C, `frame ${f}'s ${C} contacts`);
      frame.contacts = [];
      for (let k = 0; k < C; ++k) {
        frame.contacts.push({ a: u32(), b: u32(), p: [f32(), f32(), f32()], n: [f32(), f32(), f32()], depth: f32(), j: f32() });
      }
      replay.frames.push(frame);
    }
    if (at !== bytes.length) throw new Error(`replay ${what}: ${bytes.length - at} bytes after the last frame, at byte ${at}`);
    if (F === 0) throw new Error(`replay ${what}: no frames`);
    return replay;
  }
  // Float32Array views of a little-endian file are only right on little-endian machines (every
  // browser platform in use); the DataView reads above are right everywhere.

  // ---------------------------------------------------------------- scene building
  const KIND = { Sphere: 0, Box: 1, Capsule: 2, Plane: 3, Convex: 4 };
  const COLOURS = { fixed: 0x9a9a9a, particle: 0xd8743b, normal: 0xffcc00, edge: 0x202020, asleep: 0xdde8f4 };
  // A moving body's colour, by its index: neighbours in a stack or a row differ. Neither grey
  // (fixed bodies) nor yellow (the contact normals).
  const PALETTE = [0x4e79a7, 0xf28e2b, 0xe15759, 0x76b7b2, 0x59a14f, 0xb07aa1, 0xff9da7, 0x9c755f];
  const colourOf = (body, i) => (body.fixed ? COLOURS.fixed : PALETTE[i % PALETTE.length]);

  // Polygon offset pushes faces back, so that the boxes' edge lines are drawn over them
  function material(colour, opacity) {
    return new THREE.MeshStandardMaterial({
      color: colour, roughness: 0.6, metalness: 0.05, transparent: opacity < 1, opacity: opacity,
      polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
    });
  }

  // The contacts to draw for `frame`: its own, or the last recorded before it when its were left out
  const contactsOf = (replay, frame) => (frame.contactsFrom === null ? [] : replay.frames[frame.contactsFrom].contacts);

  // The three.js objects of one replay in their own scene, and update(frame) that poses them.
  function buildWorld(replay) {
    const scene = new THREE.Scene();
    scene.background = new THREE.Color(0xf4f4f0);
    scene.add(new THREE.HemisphereLight(0xffffff, 0x888877, 0.7));
    const sun = new THREE.DirectionalLight(0xffffff, 0.7);
    sun.position.set(3, -4, 8);
    scene.add(sun);

    // Boxes and spheres: one InstancedMesh per kind and colour (one buffer update a frame each)
    const groups = {};
    const singles = [];
    replay.bodies.forEach((body, i) => {
      if (body.kind === KIND.Box || body.kind === KIND.Sphere) {
        const colour = colourOf(body, i);
        const key = `${body.kind}-${body.fixed}-${colour}`;
        (groups[key] = groups[key] || { kind: body.kind, fixed: body.fixed, colour: colour, members: [] }).members.push(i);
      } else {
        singles.push(i);
      }
    });
    const instanced = [];
    for (const key in groups) {
      const g = groups[key];
      const geometry = g.kind === KIND.Box ? new THREE.BoxBufferGeometry(2, 2, 2) : new THREE.SphereBufferGeometry(1, 24, 16);
      const mesh = new THREE.InstancedMesh(geometry, material(g.colour, g.fixed && g.kind === KIND.Box ? 0.35 : 1), g.members.length);
      mesh.frustumCulled = false;  // r111 culls an InstancedMesh by its geometry's bounds alone
      scene.add(mesh);
      instanced.push({ mesh: mesh, members: g.members, kind: g.kind });
    }
    // Sleeping bodies: a pale shell a little larger than the body, per kind one InstancedMesh
    // whose count is the frame's sleepers (three r111 has no per-instance colour)
    const sleepers = replay.frames.some((f) => f.asleep !== null);
    const shells = [];
    if (sleepers) {
      for (const kind of [KIND.Box, KIND.Sphere]) {
        const members = replay.bodies.map((body, i) => i).filter((i) => replay.bodies[i].kind === kind && !replay.bodies[i].fixed);
        if (members.length === 0) continue;
        const geometry = kind === KIND.Box ? new THREE.BoxBufferGeometry(2, 2, 2) : new THREE.SphereBufferGeometry(1, 24, 16);
        const mesh = new THREE.InstancedMesh(geometry, new THREE.MeshBasicMaterial({ color: COLOURS.asleep, transparent: true, opacity: 0.75 }),
                                             members.length);
        mesh.frustumCulled = false;
        mesh.count = 0;
        scene.add(mesh);
        shells.push({ mesh: mesh, members: members, kind: kind });
      }
    }
    // Every box's 12 edges as dark lines, one LineSegments for all (EdgesGeometry of the unit box,
    // posed a frame at a time), so that a stack reads as separate cubes
    const boxes = replay.bodies.map((body, i) => i).filter((i) => replay.bodies[i].kind === KIND.Box);
    const corners = new THREE.EdgesGeometry(new THREE.BoxBufferGeometry(2, 2, 2)).attributes.position.array;
    const edgeGeometry = new THREE.BufferGeometry();
    edgeGeometry.setAttribute("position", new THREE.BufferAttribute(new Float32Array(corners.length * boxes.length), 3));
    const edges = new THREE.LineSegments(edgeGeometry, new THREE.LineBasicMaterial({ color: COLOURS.edge }));
    edges.frustumCulled = false;
    if (boxes.length > 0) scene.add(edges);
    const objects = [];  // [body index, Object3D] posed directly
    for (const i of singles) {
      const body = replay.bodies[i];
      let object;
      if (body.kind === KIND.Plane) {
        const plane = new THREE.Mesh(new THREE.PlaneBufferGeometry(6, 6), new THREE.MeshStandardMaterial({ color: 0xd8d8cc, side: THREE.DoubleSide }));
        const grid = new THREE.GridHelper(6, 30, 0xaaaaaa, 0xc4c4bc);
        grid.rotation.x = Math.PI / 2;
        grid.position.z = 0.001;
        object = new THREE.Group();
        object.add(plane, grid);
        const n = new THREE.Vector3(body.size[0], body.size[1], body.size[2]);
        object.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), n);
        object.position.copy(n.clone().multiplyScalar(body.size[3]));
        scene.add(object);
        continue;  // a plane is in the world frame: its pose never changes
      } else if (body.kind === KIND.Capsule) {
        const r = body.size[0], h = body.size[1];
        object = new THREE.Group();
        const m = material(colourOf(body, i), 1);
        const core = new THREE.Mesh(new THREE.CylinderBufferGeometry(r, r, 2 * h, 24), m);
        core.rotation.x = Math.PI / 2;  // three's cylinder runs along y, the capsule's core along body z
        const top = new THREE.Mesh(new THREE.SphereBufferGeometry(r, 24, 12), m);
        const bottom = top.clone();
        top.position.z = h;
        bottom.position.z = -h;
        object.add(core, top, bottom);
      } else {
        const geometry = new THREE.BufferGeometry();
        geometry.setAttribute("position", new THREE.Float32BufferAttribute(body.vertices, 3));
        geometry.setIndex(body.triangles);
        geometry.computeVertexNormals();
        object = new THREE.Mesh(geometry, material(colourOf(body, i), 1));
      }
      scene.add(object);
      objects.push([i, object]);
    }

    // Particles (Labs 1-2) as small spheres, one InstancedMesh, and springs as lines
    const extent = bounds(replay);
    const size = Math.max(0.5, extent.getSize(new THREE.Vector3()).length() / 2);
    let particles = null, springs = null;
    if (replay.particles > 0) {
      particles = new THREE.InstancedMesh(new THREE.SphereBufferGeometry(0.012 * size, 12, 8),
                                          new THREE.MeshStandardMaterial({ color: COLOURS.particle, roughness: 0.5 }), replay.particles);
      particles.frustumCulled = false;
      scene.add(particles);
      if (replay.springs.length > 0) {
        const lines = new THREE.BufferGeometry();
        lines.setAttribute("position", new THREE.BufferAttribute(new Float32Array(3 * replay.springs.length), 3));
        springs = new THREE.LineSegments(lines, new THREE.LineBasicMaterial({ color: 0x555555 }));
        springs.frustumCulled = false;
        scene.add(springs);
      }
    }
    // A scene without a ground plane gets a grid under it, so that up and scale read at a glance
    if (!replay.bodies.some((body) => body.kind === KIND.Plane)) {
      const grid = new THREE.GridHelper(4 * size, 20, 0xbbbbbb, 0xdddddd);
      grid.rotation.x = Math.PI / 2;
      grid.position.set(extent.getCenter(new THREE.Vector3()).x, extent.getCenter(new THREE.Vector3()).y, extent.min.z - 0.1 * size);
      scene.add(grid);
    }

    // Contacts: points coloured by depth, normals as arrows (shaft lines and instanced cone heads)
    const maxContacts = Math.max(1, ...replay.frames.map((f) => f.contacts.length));
    const contactGeometry = new THREE.BufferGeometry();
    contactGeometry.setAttribute("position", new THREE.BufferAttribute(new Float32Array(3 * maxContacts), 3));
    contactGeometry.setAttribute("color", new THREE.BufferAttribute(new Float32Array(3 * maxContacts), 3));
    const contactPoints = new THREE.Points(contactGeometry, new THREE.PointsMaterial({ size: 7, sizeAttenuation: false, vertexColors: THREE.VertexColors, depthTest: false }));
    const shaftGeometry = new THREE.BufferGeometry();
    shaftGeometry.setAttribute("position", new THREE.BufferAttribute(new Float32Array(6 * maxContacts), 3));
    const shafts = new THREE.LineSegments(shaftGeometry, new THREE.LineBasicMaterial({ color: COLOURS.normal, depthTest: false }));
    const heads = new THREE.InstancedMesh(new THREE.ConeBufferGeometry(0.012, 0.04, 8), new THREE.MeshBasicMaterial({ color: COLOURS.normal, depthTest: false }), maxContacts);
    for (const o of [contactPoints, shafts, heads]) { o.frustumCulled = false; o.renderOrder = 1; scene.add(o); }

    const matrix = new THREE.Matrix4(), position = new THREE.Vector3(), quaternion = new THREE.Quaternion(), scale = new THREE.Vector3();
    const yAxis = new THREE.Vector3(0, 1, 0), normal = new THREE.Vector3();
    const pose = (frame, i) => {
      const p = frame.poses;
      position.set(p[7 * i], p[7 * i + 1], p[7 * i + 2]);
      quaternion.set(p[7 * i + 4], p[7 * i + 5], p[7 * i + 6], p[7 * i + 3]);  // three: (x, y, z, w)
    };

    function update(frame, showContacts) {
      for (const g of instanced) {
        g.members.forEach((i, k) => {
          const s = replay.bodies[i].size;
          pose(frame, i);
          if (g.kind === KIND.Box) scale.set(s[0], s[1], s[2]); else scale.set(s[0], s[0], s[0]);
          g.mesh.setMatrixAt(k, matrix.compose(position, quaternion, scale));
        });
        g.mesh.instanceMatrix.needsUpdate = true;
      }
      for (const shell of shells) {
        let count = 0;
        for (const i of shell.members) {
          if (frame.asleep === null || !frame.asleep[i]) continue;
          const s = replay.bodies[i].size;
          pose(frame, i);
          const grow = 1.04;  // just outside the body, so the shell hides its colour
          if (shell.kind === KIND.Box) scale.set(grow * s[0], grow * s[1], grow * s[2]); else scale.setScalar(grow * s[0]);
          shell.mesh.setMatrixAt(count++, matrix.compose(position, quaternion, scale));
        }
        shell.mesh.count = count;
        shell.mesh.instanceMatrix.needsUpdate = true;
      }
      const e = edgeGeometry.attributes.position.array, corner = new THREE.Vector3();
      boxes.forEach((i, k) => {
        const s = replay.bodies[i].size;
        pose(frame, i);
        for (let c = 0; c < corners.length; c += 3) {
          corner.set(corners[c] * s[0], corners[c + 1] * s[1], corners[c + 2] * s[2]).applyQuaternion(quaternion).add(position);
          const at = k * corners.length + c;
          e[at] = corner.x; e[at + 1] = corner.y; e[at + 2] = corner.z;
        }
      });
      edgeGeometry.attributes.position.needsUpdate = true;
      for (const [i, object] of objects) {
        pose(frame, i);
        object.position.copy(position);
        object.quaternion.copy(quaternion);
      }
      if (particles) {
        scale.set(1, 1, 1);
        quaternion.set(0, 0, 0, 1);
        for (let k = 0; k < replay.particles; ++k) {
          particles.setMatrixAt(k, matrix.compose(position.fromArray(frame.particles, 3 * k), quaternion, scale));
        }
        particles.instanceMatrix.needsUpdate = true;
        if (springs) {
          const a = springs.geometry.attributes.position.array;
          replay.springs.forEach((p, k) => a.set(frame.particles.subarray(3 * p, 3 * p + 3), 3 * k));
          springs.geometry.attributes.position.needsUpdate = true;
        }
      }
      const contacts = contactsOf(replay, frame);
      const n = showContacts ? contacts.length : 0;
      const cp = contactGeometry.attributes.position.array, cc = contactGeometry.attributes.color.array;
      const sp = shaftGeometry.attributes.position.array;
      contacts.slice(0, n).forEach((c, k) => {
        cp.set(c.p, 3 * k);
        const red = Math.min(1, c.depth / 0.005);  // red at 5 mm of overlap and deeper, green when touching
        cc.set([red, 1 - red, 0], 3 * k);
        const length = 0.05 + Math.min(0.1, 5 * c.depth);  // 5 cm, and 5 mm longer per mm of depth up to 15 cm
        normal.set(c.n[0], c.n[1], c.n[2]);
        sp.set(c.p, 6 * k);
        sp.set([c.p[0] + length * c.n[0], c.p[1] + length * c.n[1], c.p[2] + length * c.n[2]], 6 * k + 3);
        position.set(c.p[0], c.p[1], c.p[2]).addScaledVector(normal, length);
        quaternion.setFromUnitVectors(yAxis, normal);
        heads.setMatrixAt(k, matrix.compose(position, quaternion, scale.set(1, 1, 1)));
      });
      contactGeometry.setDrawRange(0, n);
      contactGeometry.attributes.position.needsUpdate = true;
      contactGeometry.attributes.color.needsUpdate = true;
      shaftGeometry.setDrawRange(0, 2 * n);
      shaftGeometry.attributes.position.needsUpdate = true;
      heads.count = n;
      heads.instanceMatrix.needsUpdate = true;
    }
    return { scene: scene, update: update };
  }

  // Where the bodies (planes left out) and particles go over the run, from 20 frames spread over
  // it: where the camera looks, and from how far.
  function bounds(replay) {
    const box = new THREE.Box3(), point = new THREE.Vector3();
    const stride = Math.max(1, Math.floor(replay.frames.length / 20));
    for (let f = 0; f < replay.frames.length; f += stride) {
      const frame = replay.frames[f];
      replay.bodies.forEach((body, i) => {
        if (body.kind === KIND.Plane) return;
        const r = body.kind === KIND.Box ? Math.hypot(body.size[0], body.size[1], body.size[2]) : Math.max(body.size[0], 0.1);
        point.fromArray(frame.poses, 7 * i);
        box.expandByPoint(point.clone().addScalar(r));
        box.expandByPoint(point.clone().addScalar(-r));
      });
      for (let k = 0; k < replay.particles; ++k) box.expandByPoint(point.fromArray(frame.particles, 3 * k));
    }
    if (box.isEmpty()) box.set(new THREE.Vector3(-1, -1, 0), new THREE.Vector3(1, 1, 1));
    return box;
  }

  // ---------------------------------------------------------------- energy plot
  // About `count` round steps (1, 2 or 5 times a power of ten) from lo to hi
  function ticks(lo, hi, count) {
    const raw = (hi - lo) / count, power = Math.pow(10, Math.floor(Math.log10(raw)));
    const step = power * (raw / power < 1.5 ? 1 : raw / power < 3.5 ? 2 : raw / power < 7.5 ? 5 : 10);
    const out = [];
    for (let v = Math.ceil(lo / step) * step; v <= hi + 1e-9 * step; v += step) out.push(Math.abs(v) < 1e-12 * step ? 0 : v);
    return out;
  }
  const tickText = (v, step) => (v === 0 ? "0" : Math.abs(step) >= 1e-2 && Math.abs(v) < 1e5 ? String(+v.toFixed(Math.max(0, -Math.floor(Math.log10(step))))) : v.toExponential(1));

  // What the plot shows of the runs: kinetic, potential and total energy in J, or, when every
  // run's total is flat (its range under 1% of its size), the total's relative drift
  // (E - E0)/|E0| (E - E0 in J when E0 is 0), which shows what the joules would hide.
  function energySeries(replays) {
    const totals = replays.map((r) => r.frames.map((f) => f.kinetic + f.potential));
    const flat = totals.every((e) => {
      const finite = e.filter(isFinite);
      if (finite.length === 0) return false;
      const lo = Math.min(...finite), hi = Math.max(...finite);
      return hi - lo <= 0.01 * Math.max(Math.abs(lo), Math.abs(hi));
    });
    const series = [];
    replays.forEach((r, k) => {
      const dash = k === 0 ? [] : [5, 4], t = r.frames.map((f) => f.time);
      if (flat) {
        const e0 = totals[k][0];
        series.push({ t: t, v: totals[k].map((e) => (e0 !== 0 ? (e - e0) / Math.abs(e0) : e - e0)), colour: "#222", dash: dash });
      } else {
        series.push({ t: t, v: r.frames.map((f) => f.kinetic), colour: "#d0453b", dash: dash });
        series.push({ t: t, v: r.frames.map((f) => f.potential), colour: "#3b7dd8", dash: dash });
        series.push({ t: t, v: totals[k], colour: "#222", dash: dash });
      }
    });
    const e0 = totals[0][0];
    const axis = !flat ? "energy [J]" : e0 !== 0 ? "(E-E0)/|E0|" : "E-E0 [J]";
    const legend = !flat
      ? '<span style="color:#d0453b">kinetic</span>, <span style="color:#3b7dd8">potential</span> and total (black) [J]'
      : `the total is flat (E0 = ${e0.toPrecision(4)} J), so the plot shows its ${e0 !== 0 ? "relative drift (E - E0)/|E0|" : "drift E - E0 [J]"}`;
    return { series: series, flat: flat, axis: axis, legend: legend };
  }

  function drawEnergy(canvas, plot, time) {
    const g = canvas.getContext("2d");
    const w = canvas.width, h = canvas.height, left = 62, right = 8, top = 8, bottom = 28;
    g.clearRect(0, 0, w, h);
    let lo = Infinity, hi = -Infinity, t0 = Infinity, t1 = -Infinity;
    for (const s of plot.series) {
      for (const v of s.v) if (isFinite(v)) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
      t0 = Math.min(t0, s.t[0]); t1 = Math.max(t1, s.t[s.t.length - 1]);
    }
    if (!(hi > lo)) { const pad = Math.max(Math.abs(lo) * 0.1, plot.flat ? 1e-9 : 1); hi = lo + pad; lo -= pad; }
    if (!(t1 > t0)) t1 = t0 + 1;
    const x = (t) => left + (w - left - right) * (t - t0) / (t1 - t0);
    const y = (v) => h - bottom - (h - top - bottom) * (v - lo) / (hi - lo);
    // Axes with their ticks and labels
    g.font = "11px sans-serif"; g.fillStyle = "#444"; g.strokeStyle = "#999"; g.lineWidth = 1; g.setLineDash([]);
    g.beginPath(); g.moveTo(left, top); g.lineTo(left, h - bottom); g.lineTo(w - right, h - bottom); g.stroke();
    const yTicks = ticks(lo, hi, 4), tTicks = ticks(t0, t1, 8);
    g.textAlign = "right"; g.textBaseline = "middle";
    for (const v of yTicks) {
      g.strokeStyle = "#eee"; g.beginPath(); g.moveTo(left + 1, y(v)); g.lineTo(w - right, y(v)); g.stroke();
      g.fillText(tickText(v, yTicks.length > 1 ? yTicks[1] - yTicks[0] : v), left - 4, y(v));
    }
    g.textAlign = "center"; g.textBaseline = "top";
    for (const t of tTicks) {
      g.strokeStyle = "#999"; g.beginPath(); g.moveTo(x(t), h - bottom); g.lineTo(x(t), h - bottom + 3); g.stroke();
      g.fillText(tickText(t, tTicks.length > 1 ? tTicks[1] - tTicks[0] : 1), x(t), h - bottom + 4);
    }
    g.fillText("t [s]", w - right - 14, h - 12);
    g.save(); g.font = "10px sans-serif"; g.translate(10, top + (h - top - bottom) / 2); g.rotate(-Math.PI / 2); g.textBaseline = "middle";
    g.fillText(plot.axis, 0, 0); g.restore();
    for (const s of plot.series) {
      g.strokeStyle = s.colour; g.setLineDash(s.dash); g.lineWidth = 1.5; g.beginPath();
      s.v.forEach((v, i) => (i ? g.lineTo(x(s.t[i]), y(v)) : g.moveTo(x(s.t[i]), y(v))));
      g.stroke();
    }
    g.setLineDash([]); g.strokeStyle = "#0a0"; g.lineWidth = 2; g.beginPath();
    g.moveTo(x(time), top); g.lineTo(x(time), h - bottom); g.stroke();
  }

  // ---------------------------------------------------------------- the page
  function main() {
    if (data.error) { fail(data.error); return; }
    const replays = data.replays.map((r) => decodeReplay(r.base64, r.name));
    const labels = data.replays.map((r) => r.label);
    const first = replays[0];
    $("title").textContent = first.title;
    $("settings").textContent = replays.map((r, k) => (replays.length > 1 ? labels[k] + ": " : "") + (r.settings || "(no settings recorded)")).join("\n");
    $("legend-reference").hidden = replays.length < 2;
    if (data.note) { $("note").textContent = data.note; $("note").hidden = false; }
    // The page steps through the first replay's frames; another shows its last frame at or before
    // the same time (a recorded reference may hold fewer frames: ./physlab publish thins it)
    const frames = first.frames.length;
    const match = replays.map((r) => {
      let j = 0;
      return first.frames.map((f) => {
        while (j + 1 < r.frames.length && r.frames[j + 1].time <= f.time + 1e-6) ++j;
        return j;
      });
    });
    const plot = energySeries(replays);
    $("energy-legend").innerHTML = plot.legend;
    $("frame-count").textContent = String(frames);
    $("bodies").textContent = `${first.bodies.length} bodies, ${first.particles} particles`;
    if (data.diff) {
      $("diff").textContent = data.diff.text;
      $("diff").hidden = false;
      $("diff").classList.toggle("agree", data.diff.frame === null);
      if (data.diff.frame !== null) {
        const mark = $("diff-mark");
        mark.style.left = `${(100 * data.diff.frame) / Math.max(1, frames - 1)}%`;
        mark.title = data.diff.text;
        mark.hidden = false;
      }
    }

    const canvas = $("view");
    const renderer = new THREE.WebGLRenderer({ canvas: canvas, antialias: true, preserveDrawingBuffer: true });
    renderer.setPixelRatio(window.devicePixelRatio || 1);
    const worlds = replays.map(buildWorld);
    const box = bounds(first);
    const centre = box.getCenter(new THREE.Vector3()), radius = Math.max(0.5, box.getSize(new THREE.Vector3()).length() / 2);
    const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 200);
    camera.up.set(0, 0, 1);  // z up (conventions page)
    camera.position.copy(centre).add(new THREE.Vector3(1.6, -2.4, 1.2).multiplyScalar(radius * 0.9));
    const controls = new THREE.OrbitControls(camera, canvas);
    controls.target.copy(centre);
    controls.update();

    const slider = $("slider");
    slider.max = String(frames - 1);
    let index = 0, playing = !/frame=/.test(location.hash), clock = null;

    function render() {
      const w = canvas.clientWidth, h = canvas.clientHeight;
      renderer.setSize(w, h, false);
      const part = w / worlds.length;
      camera.aspect = part / h;
      camera.updateProjectionMatrix();
      renderer.setScissorTest(true);
      worlds.forEach((world, k) => {
        renderer.setViewport(k * part, 0, part, h);
        renderer.setScissor(k * part, 0, part, h);
        renderer.render(world.scene, camera);
      });
    }

    function show(i) {
      index = Math.max(0, Math.min(frames - 1, i));
      const contacts = $("contacts").checked;
      worlds.forEach((world, k) => world.update(replays[k].frames[match[k][index]], contacts));
      slider.value = String(index);
      const f = first.frames[index];
      $("frame-index").textContent = String(index + 1);
      $("time").textContent = f.time.toFixed(3);
      const deepest = contactsOf(first, f).reduce((d, c) => Math.max(d, c.depth), 0);
      $("stats").textContent = replays.map((r, k) => {
        const at = match[k][index], g = r.frames[at];
        const from = g.contactsFrom === null || g.contactsFrom === at ? "" : ` of t = ${r.frames[g.contactsFrom].time.toFixed(3)} s (contacts recorded on some frames only)`;
        return (replays.length > 1 ? labels[k] + ": " : "") +
          `KE ${g.kinetic.toPrecision(5)} J, PE ${g.potential.toPrecision(5)} J, ${contactsOf(r, g).length} contacts${from}` +
          `${k === 0 ? ` (deepest ${(1000 * deepest).toFixed(2)} mm)` : ""}, ${g.iterations} iterations` +
          (g.asleep === null ? "" : `, ${g.asleep.reduce((n, a) => n + a, 0)} bodies asleep`);
      }).join("; ");
      drawEnergy($("energy"), plot, f.time);
      render();
    }

    function tick(now) {
      if (playing) {
        if (clock === null) clock = { wall: now, time: first.frames[index].time };
        const t = clock.time + (now - clock.wall) / 1000;
        let i = index;
        while (i + 1 < frames && first.frames[i + 1].time <= t) ++i;
        if (i === frames - 1 && index === frames - 1) { playing = false; $("play").textContent = "play"; }
        if (i !== index) show(i);
      }
      requestAnimationFrame(tick);
    }

    const pause = () => { playing = false; clock = null; $("play").textContent = "play"; };
    $("play").onclick = () => {
      if (playing) { pause(); return; }
      if (index === frames - 1) show(0);
      playing = true; clock = null; $("play").textContent = "pause";
    };
    $("back").onclick = () => { pause(); show(index - 1); };
    $("forward").onclick = () => { pause(); show(index + 1); };
    slider.oninput = () => { pause(); show(Number(slider.value)); };
    $("contacts").onchange = () => show(index);
    controls.addEventListener("change", render);
    window.addEventListener("resize", render);
    window.addEventListener("keydown", (e) => {
      if (e.key === " ") { e.preventDefault(); $("play").click(); }
      if (e.key === "ArrowLeft") $("back").click();
      if (e.key === "ArrowRight") $("forward").click();
    });

    // #frame=N (1-based) or #frame=last opens paused at that frame (the browser test uses it);
    // #contacts draws the contacts from the start
    $("contacts").checked = /contacts/.test(location.hash);
    const wanted = /frame=(last|\d+)/.exec(location.hash);
    show(wanted ? (wanted[1] === "last" ? frames - 1 : Number(wanted[1]) - 1) : 0);
    // #measure shows every frame once, as playing does (poses, contacts, the panel, the energy
    // plot), waiting for the GPU after each, and writes the time per frame into #measured
    if (/measure/.test(location.hash)) {
      const gl = renderer.getContext(), times = [];
      for (let i = 0; i < frames; ++i) {
        const start = performance.now();
        show(i);
        gl.finish();
        times.push(performance.now() - start);
      }
      times.sort((a, b) => a - b);
      const mean = times.reduce((a, b) => a + b, 0) / frames;
      $("measured").textContent = `${frames} frames, ${mean.toFixed(2)} ms per frame (median ${times[frames >> 1].toFixed(2)}, slowest ${times[frames - 1].toFixed(2)})`;
    }
    $("play").textContent = playing ? "pause" : "play";
    requestAnimationFrame(tick);
  }

  try {
    main();
  } catch (e) {
    fail(`The viewer could not show this replay: ${e.message}`);
  }
})();
