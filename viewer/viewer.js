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
  const VERSION = 2;

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
      const recorded = version === 1 || (u32() & 1) !== 0;
      if (!recorded && C !== 0) throw new Error(`replay ${what}: frame ${f} holds ${C} contacts but says they were not recorded`);
      frame.contactsFrom = recorded ? f : (f > 0 ? replay.frames[f - 1].contactsFrom : null);
      need(28 * B, `frame ${f}'s poses`);
      frame.poses = new Float32Array(bytes.buffer.slice(at, at + 28 * B)); at += 28 * B;
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
  const COLOURS = { moving: 0x3b7dd8, fixed: 0x9a9a9a, particle: 0xd8743b, normal: 0xffcc00 };

  function material(fixed, opacity) {
    return new THREE.MeshStandardMaterial({
      color: fixed ? COLOURS.fixed : COLOURS.moving, roughness: 0.6, metalness: 0.05,
      transparent: opacity < 1, opacity: opacity,
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

    // Boxes and spheres, moving and fixed: one InstancedMesh each (one buffer update a frame)
    const groups = {};
    const singles = [];
    replay.bodies.forEach((body, i) => {
      if (body.kind === KIND.Box || body.kind === KIND.Sphere) {
        const key = `${body.kind}-${body.fixed}`;
        (groups[key] = groups[key] || { kind: body.kind, fixed: body.fixed, members: [] }).members.push(i);
      } else {
        singles.push(i);
      }
    });
    const instanced = [];
    for (const key in groups) {
      const g = groups[key];
      const geometry = g.kind === KIND.Box ? new THREE.BoxBufferGeometry(2, 2, 2) : new THREE.SphereBufferGeometry(1, 24, 16);
      const mesh = new THREE.InstancedMesh(geometry, material(g.fixed, g.fixed && g.kind === KIND.Box ? 0.35 : 1), g.members.length);
      mesh.frustumCulled = false;  // r111 culls an InstancedMesh by its geometry's bounds alone
      scene.add(mesh);
      instanced.push({ mesh: mesh, members: g.members, kind: g.kind });
    }
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
        const m = material(body.fixed, 1);
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
        object = new THREE.Mesh(geometry, material(body.fixed, 1));
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
  function drawEnergy(canvas, replays, index) {
    const g = canvas.getContext("2d");
    const w = canvas.width, h = canvas.height, pad = 4;
    g.clearRect(0, 0, w, h);
    const series = [];
    replays.forEach((r, k) => {
      const dash = k === 0 ? [] : [5, 4];
      series.push({ v: r.frames.map((f) => f.kinetic), colour: "#d0453b", dash: dash });
      series.push({ v: r.frames.map((f) => f.potential), colour: "#3b7dd8", dash: dash });
      series.push({ v: r.frames.map((f) => f.kinetic + f.potential), colour: "#222", dash: dash });
    });
    let lo = Infinity, hi = -Infinity;
    for (const s of series) for (const v of s.v) if (isFinite(v)) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
    if (!(hi > lo)) { hi = lo + 1; lo -= 1; }
    const n = replays[0].frames.length;
    const x = (i) => pad + (w - 2 * pad) * (n > 1 ? i / (n - 1) : 0);
    const y = (v) => h - pad - (h - 2 * pad) * (v - lo) / (hi - lo);
    for (const s of series) {
      g.strokeStyle = s.colour; g.setLineDash(s.dash); g.lineWidth = 1.5; g.beginPath();
      s.v.forEach((v, i) => (i ? g.lineTo(x(i), y(v)) : g.moveTo(x(i), y(v))));
      g.stroke();
    }
    g.setLineDash([]); g.strokeStyle = "#0a0"; g.lineWidth = 2; g.beginPath();
    g.moveTo(x(index), 0); g.lineTo(x(index), h); g.stroke();
    $("energy-range").textContent = `${lo.toPrecision(4)} J to ${hi.toPrecision(4)} J`;
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
    const frames = Math.min(...replays.map((r) => r.frames.length));
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
      worlds.forEach((world, k) => world.update(replays[k].frames[index], contacts));
      slider.value = String(index);
      const f = first.frames[index];
      $("frame-index").textContent = String(index + 1);
      $("time").textContent = f.time.toFixed(3);
      const deepest = contactsOf(first, f).reduce((d, c) => Math.max(d, c.depth), 0);
      $("stats").textContent = replays.map((r, k) => {
        const g = r.frames[index];
        const from = g.contactsFrom === null || g.contactsFrom === index ? "" : ` of frame ${g.contactsFrom + 1} (contacts recorded on some frames only)`;
        return (replays.length > 1 ? labels[k] + ": " : "") +
          `KE ${g.kinetic.toPrecision(5)} J, PE ${g.potential.toPrecision(5)} J, ${contactsOf(r, g).length} contacts${from}` +
          `${k === 0 ? ` (deepest ${(1000 * deepest).toFixed(2)} mm)` : ""}, ${g.iterations} iterations`;
      }).join("; ");
      drawEnergy($("energy"), replays, index);
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
