// The curved-space viewer (tilekit/plugins/curved/web.py): the patch arrives once as model
// points; the view is a 3x3 matrix V on the model (a Lorentz matrix of the hyperboloid, a
// rotation of the sphere). A drag composes onto the view at the drag's start, V0, the motion
// taking the start point to the current point: the hyperbolic translation along their
// geodesic (Poincaré disc, edges redrawn as true arcs), or the rotation about the axis
// through both (the sphere, in either view). Hyperbolic views are rebased by the tiling's own
// symmetries (V <- V g), which leaves the picture as it is and keeps the patch round the
// screen's centre. The wheel and a two-finger pinch magnify the picture (a Euclidean zoom of
// the drawing, 1x to 16x, by the SVG's viewBox) about the point under the pointer or between
// the fingers, which stays where it is; the reset button restores view and zoom.
// The tile editor (editor.js) changes data-src and sends the "curved-reload" event: the patch
// is fetched again (the newest request wins) and redrawn in the same view and zoom; each
// patch drawn is announced by a "curved-loaded" event carrying the payload, a refusal by
// "curved-refused" (the last patch stays on screen). With data-mark-home the face placed by
// the identity (the prototile) is drawn with a heavier outline.
// The sphere has two views (data-projection, the page's #projection control and ?view=, which
// the address bar follows): orthographic (the far side faint) and stereographic, with the
// conventions of render.py's stereographic view (tilekit render --set plane=stereographic):
// projected from the point opposite the screen's centre, (x, y) / (1 + z) on the turned
// sphere, scaled so that the equator has radius STEREO_R; every piece of an outline (its
// points are samples along geodesics) is the true arc of the circle through its projected
// ends and midpoint, in two SVG arcs; the face holding the projection's pole is drawn as the
// outside (a frame round the view less its boundary, even-odd). A drag turns the sphere by
// the rotation taking the sphere point under the drag's start to the one under the pointer,
// so the point under the pointer stays under it; switching views keeps the rotation.
(function () {
  "use strict";
  const root = document.getElementById("curved");
  if (!root) return;
  const view = document.getElementById("view");
  const errorBox = document.getElementById("error");
  const status = document.getElementById("status");
  const NS = "http://www.w3.org/2000/svg";
  const PAD = 1.02;
  let data = null, V = eye(), V0 = null, start = null, starts = [], svg = null, paths = [];
  let syms = [], rebase = 0.9, hyper = true, frame = 0, rim = null;
  const STEREO_R = 0.3, FRAME = 2; // the equator's radius; the outside's frame (holds the view at 1x)
  let stereo = root.dataset.projection === "stereographic";
  const choice = document.getElementById("projection");
  if (choice) choice.value = stereo ? "stereographic" : "orthographic"; // not a form value the browser restored
  root.dataset.equator = String(STEREO_R);
  const MAX_ZOOM = 16;
  let zoom = 1, centre = [0, 0]; // the viewBox: centre (SVG coordinates, y down) and magnification
  const touches = new Map(); let pinch = null;

  function eye() { return [1, 0, 0, 0, 1, 0, 0, 0, 1]; }
  function mul(a, b) {
    const c = new Array(9);
    for (let i = 0; i < 3; i++) for (let j = 0; j < 3; j++)
      c[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
    return c;
  }
  function apply(m, x, y, z) {
    return [m[0] * x + m[1] * y + m[2] * z, m[3] * x + m[4] * y + m[5] * z, m[6] * x + m[7] * y + m[8] * z];
  }
  // the pure boost taking the pole (0, 0, 1) to the hyperboloid point (x, y, t)
  function boost(x, y, t) {
    const k = 1 / (1 + t);
    return [1 + x * x * k, x * y * k, x, x * y * k, 1 + y * y * k, y, x, y, t];
  }
  function fromDisc(p) {
    const r2 = p[0] * p[0] + p[1] * p[1];
    return [2 * p[0] / (1 - r2), 2 * p[1] / (1 - r2), (1 + r2) / (1 - r2)];
  }
  // the hyperbolic translation taking disc point a to disc point b (along their geodesic):
  // conjugate by the boost to a the boost from the pole to w, the image of b brought back
  function translation(a, b) {
    const A = fromDisc(a), B = fromDisc(b);
    const toA = boost(A[0], A[1], A[2]), fromA = boost(-A[0], -A[1], A[2]);
    const w = apply(fromA, B[0], B[1], B[2]);
    return mul(mul(toA, boost(w[0], w[1], w[2])), fromA);
  }
  function onSphere(p) {
    const r2 = p[0] * p[0] + p[1] * p[1];
    if (r2 >= 1) { const r = Math.sqrt(r2); return [p[0] / r, p[1] / r, 0]; }
    return [p[0], p[1], Math.sqrt(1 - r2)];
  }
  // the sphere point whose stereographic image (scaled by STEREO_R) is the plane point p
  function fromPlane(p) {
    const u = p[0] / STEREO_R, v = p[1] / STEREO_R, r2 = u * u + v * v;
    return [2 * u / (1 + r2), 2 * v / (1 + r2), (1 - r2) / (1 + r2)];
  }
  function sphereAt(p) { return stereo ? fromPlane(p) : onSphere(p); }
  // the rotation about A x B taking the unit vector A to B (Rodrigues)
  function rotation(A, B) {
    let k = [A[1] * B[2] - A[2] * B[1], A[2] * B[0] - A[0] * B[2], A[0] * B[1] - A[1] * B[0]];
    const s = Math.hypot(k[0], k[1], k[2]), c = A[0] * B[0] + A[1] * B[1] + A[2] * B[2];
    if (s < 1e-15) return eye();
    k = k.map(function (v) { return v / s; });
    const K = [0, -k[2], k[1], k[2], 0, -k[0], -k[1], k[0], 0], K2 = mul(K, K);
    return eye().map(function (v, i) { return v + s * K[i] + (1 - c) * K2[i]; });
  }
  // back onto O(2,1): Gram-Schmidt in the Lorentz form, the time-like column first
  function clean(m) {
    const col = function (j) { return [m[j], m[3 + j], m[6 + j]]; };
    const dot = function (u, v) { return u[0] * v[0] + u[1] * v[1] - u[2] * v[2]; };
    let t = col(2); const nt = Math.sqrt(-dot(t, t)); t = t.map(function (v) { return v / nt; });
    let x = col(0); let d = dot(x, t);
    x = x.map(function (v, i) { return v + d * t[i]; }); const nx = Math.sqrt(dot(x, x)); x = x.map(function (v) { return v / nx; });
    let y = col(1); d = dot(y, t); const e = dot(y, x);
    y = y.map(function (v, i) { return v + d * t[i] - e * x[i]; }); const ny = Math.sqrt(dot(y, y)); y = y.map(function (v) { return v / ny; });
    return [x[0], y[0], t[0], x[1], y[1], t[1], x[2], y[2], t[2]];
  }
  // the point under the screen's centre, V^-1 (pole): for a Lorentz V, J V^T J (pole)
  function centreOf(m) { return [-m[6], -m[7], m[8]]; }
  function dist(g, c) { // cosh of the distance from g(pole) to the hyperboloid point c
    return -(g[2] * c[0] + g[5] * c[1] - g[8] * c[2]);
  }
  function rebaseView() {
    let moved = false;
    for (let step = 0; step < 200; step++) {
      const c = centreOf(V);
      if (c[2] <= Math.cosh(rebase)) break;
      let best = null, bestD = c[2] * (1 - 1e-12);
      syms.forEach(function (g) { const d = dist(g, c); if (d < bestD) { best = g; bestD = d; } });
      if (!best) break;
      V = clean(mul(V, best));
      if (V0) V0 = clean(mul(V0, best));
      moved = true;
    }
    if (moved) root.dataset.rebases = String(Number(root.dataset.rebases || 0) + 1);
  }
  function fmt(v) { return v.toFixed(6); }
  function arc(a, b) { // SVG command for the geodesic from disc point a to b (y flipped)
    const det = a[0] * b[1] - a[1] * b[0], ra = a[0] * a[0] + a[1] * a[1], rb = b[0] * b[0] + b[1] * b[1];
    if (Math.abs(det) < 1e-12 * Math.max(1e-300, Math.sqrt(Math.max(ra, rb)))) return "L" + fmt(b[0]) + " " + fmt(-b[1]);
    const ka = (ra + 1) / 2, kb = (rb + 1) / 2;
    const cx = (ka * b[1] - kb * a[1]) / det, cy = (a[0] * kb - b[0] * ka) / det;
    const r = Math.sqrt(Math.max(cx * cx + cy * cy - 1, 0));
    const cross = (a[0] - cx) * (b[1] - cy) - (a[1] - cy) * (b[0] - cx);
    return "A" + fmt(r) + " " + fmt(r) + " 0 0 " + (cross > 0 ? "0" : "1") + " " + fmt(b[0]) + " " + fmt(-b[1]);
  }
  // the sphere point q (view space) projected from (0, 0, -1), scaled; near that pole the
  // denominator is bounded away from 0 so no coordinate is infinite
  function project(q) {
    const s = STEREO_R / Math.max(1 + q[2], 1e-12);
    return [q[0] * s, q[1] * s];
  }
  function pair(p) { return fmt(p[0]) + " " + fmt(-p[1]); }
  // from a through m to b: two arcs of the circle through the three (render.py's
  // three_point_arc_commands), or a line where they are collinear
  function threePointArc(a, m, b) {
    const u = [m[0] - a[0], m[1] - a[1]], w = [b[0] - a[0], b[1] - a[1]];
    const cross = u[0] * w[1] - u[1] * w[0], ww = w[0] * w[0] + w[1] * w[1];
    if (Math.abs(cross) <= 1e-9 * ww) return "L" + pair(b);
    const uu = u[0] * u[0] + u[1] * u[1];
    const cx = (uu * w[1] - ww * u[1]) / (2 * cross), cy = (ww * u[0] - uu * w[0]) / (2 * cross);
    const r = fmt(Math.hypot(cx, cy));
    const ccw = u[0] * (b[1] - m[1]) - u[1] * (b[0] - m[0]) > 0;
    const head = "A" + r + " " + r + " 0 0 " + (ccw ? "0" : "1") + " "; // y is flipped: counter-clockwise is sweep 0
    return head + pair(m) + " " + head + pair(b);
  }
  function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
  function cross(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
  // the turn of the face's outline q (view space) about the pole (0, 0, -1), both seen in the
  // stereographic projection from the antipode o of the face's mean point (outside the face):
  // about +-2 pi for the face holding the pole, about 0 for the others. (A projection from the
  // screen's centre would not do: the face holding the centre also winds round the pole there.)
  function turnAboutPole(q) {
    const m = [0, 0, 0];
    q.forEach(function (c) { m[0] += c[0]; m[1] += c[1]; m[2] += c[2]; });
    const mn = Math.hypot(m[0], m[1], m[2]);
    const o = mn > 1e-9 ? [-m[0] / mn, -m[1] / mn, -m[2] / mn] : [0, 0, 1];
    const e1 = cross(o, Math.abs(o[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0]), n1 = Math.hypot(e1[0], e1[1], e1[2]);
    e1[0] /= n1; e1[1] /= n1; e1[2] /= n1;
    const e2 = cross(o, e1);
    const flat = function (c) { const d = Math.max(1 - dot(c, o), 1e-300); return [dot(c, e1) / d, dot(c, e2) / d]; };
    const x = flat([0, 0, -1]);
    let turn = 0, prev = null;
    for (let i = 0; i <= q.length; i++) {
      const c = flat(q[i % q.length]);
      const ang = Math.atan2(c[1] - x[1], c[0] - x[0]);
      if (prev !== null) {
        let da = ang - prev;
        if (da > Math.PI) da -= 2 * Math.PI; else if (da < -Math.PI) da += 2 * Math.PI;
        turn += da;
      }
      prev = ang;
    }
    return turn;
  }
  function drawStereo() {
    const pts = data.points;
    let off = 0, outside = -1;
    const frameD = "M" + -FRAME + " " + -FRAME + " L" + FRAME + " " + -FRAME + " L" + FRAME + " " + FRAME +
      " L" + -FRAME + " " + FRAME + " Z ";
    data.sizes.forEach(function (k, f) {
      const q = [];
      for (let i = 0; i < k; i++, off += 3) q.push(apply(V, pts[off], pts[off + 1], pts[off + 2]));
      let d = "M" + pair(project(q[0]));
      for (let i = 0; i < k; i++) {
        const a = q[i], b = q[(i + 1) % k];
        const s = [a[0] + b[0], a[1] + b[1], a[2] + b[2]], n = Math.hypot(s[0], s[1], s[2]) || 1;
        d += " " + threePointArc(project(a), project([s[0] / n, s[1] / n, s[2] / n]), project(b));
      }
      const el = paths[f];
      const holds = outside < 0 && Math.abs(turnAboutPole(q)) > Math.PI;
      if (holds) { outside = f; el.dataset.tile = "outside"; } else delete el.dataset.tile;
      el.setAttribute("d", (holds ? frameD : "") + d + " Z");
      el.setAttribute("fill-rule", "evenodd");
      el.setAttribute("fill-opacity", "1");
      el.setAttribute("stroke-opacity", "1");
    });
    root.dataset.outside = String(outside);
  }
  function draw() {
    rim.setAttribute("display", !hyper && stereo ? "none" : "inline");
    if (!hyper && stereo) { drawStereo(); finish(); return; }
    delete root.dataset.outside;
    const pts = data.points;
    let off = 0;
    const order = [];
    data.sizes.forEach(function (k, f) {
      const flat = [];
      let front = 0;
      for (let i = 0; i < k; i++, off += 3) {
        const q = apply(V, pts[off], pts[off + 1], pts[off + 2]);
        if (hyper) flat.push([q[0] / (1 + q[2]), q[1] / (1 + q[2])]);
        else {
          front += q[2];
          const r = Math.hypot(q[0], q[1]) || 1;
          flat.push(q[2] >= 0 ? [q[0], q[1]] : [q[0] / r, q[1] / r]);
        }
      }
      let d = "M" + fmt(flat[0][0]) + " " + fmt(-flat[0][1]);
      for (let i = 0; i < k; i++) {
        const b = flat[(i + 1) % k];
        d += " " + (hyper ? arc(flat[i], b) : "L" + fmt(b[0]) + " " + fmt(-b[1]));
      }
      const el = paths[f];
      el.setAttribute("d", d + " Z");
      if (!hyper) {
        delete el.dataset.tile;
        el.setAttribute("fill-opacity", front >= 0 ? "1" : "0.2");
        el.setAttribute("stroke-opacity", front >= 0 ? "1" : "0.2");
        order.push([front, el]);
      }
    });
    if (!hyper) order.sort(function (a, b) { return a[0] - b[0]; }).forEach(function (p) { svg.appendChild(p[1]); });
    finish();
  }
  function finish() {
    root.dataset.view = V.map(function (v) { return v.toPrecision(12); }).join(",");
    root.dataset.renders = String(Number(root.dataset.renders || 0) + 1);
  }
  function later() {
    if (frame) return;
    frame = requestAnimationFrame(function () { frame = 0; draw(); });
  }
  function discPoint(ev) { // the pointer in model-plane coordinates (y up)
    const m = svg.getScreenCTM().inverse();
    const p = svg.createSVGPoint(); p.x = ev.clientX; p.y = ev.clientY;
    const q = p.matrixTransform(m);
    return [q.x, -q.y];
  }
  function svgPoint(x, y) { // client pixels to SVG coordinates (y down)
    const p = svg.createSVGPoint(); p.x = x; p.y = y;
    return p.matrixTransform(svg.getScreenCTM().inverse());
  }
  function setBox() {
    const half = PAD / zoom, room = PAD - half;
    centre = centre.map(function (v) { return Math.max(-room, Math.min(room, v)); });
    svg.setAttribute("viewBox", [centre[0] - half, centre[1] - half, 2 * half, 2 * half].join(" "));
    root.dataset.zoom = zoom.toFixed(6);
  }
  // magnify to z about the SVG point m, from the zoom z0 and centre c0 (m stays put)
  function zoomAbout(m, z, z0, c0) {
    z = Math.max(1, Math.min(MAX_ZOOM, z));
    centre = [m.x + (c0[0] - m.x) * z0 / z, m.y + (c0[1] - m.y) * z0 / z];
    zoom = z;
    setBox();
  }
  function inside(p) { return (!hyper && stereo) || p[0] * p[0] + p[1] * p[1] < (hyper ? 0.9999 : 1); }
  function build(keep) {
    svg = document.createElementNS(NS, "svg");
    svg.setAttribute("id", "disc");
    svg.style.touchAction = "none"; // pinches reach the page's handlers, not the browser's zoom
    if (!keep) { zoom = 1; centre = [0, 0]; }
    setBox();
    rim = document.createElementNS(NS, "circle");
    Object.entries({ cx: 0, cy: 0, r: 1, fill: hyper ? "#f8f8f8" : "#eef2f6", stroke: "#222", "stroke-width": 0.004 })
      .forEach(function (kv) { rim.setAttribute(kv[0], kv[1]); });
    svg.appendChild(rim);
    paths = data.sizes.map(function (k, f) {
      const el = document.createElementNS(NS, "path");
      el.setAttribute("fill", data.palette[data.colour[f] % data.palette.length]);
      el.setAttribute("stroke", "#222");
      el.setAttribute("stroke-width", "0.003");
      el.setAttribute("stroke-linejoin", "round");
      el.dataset.face = String(f);
      if (root.dataset.markHome !== undefined && f === data.home) {
        el.setAttribute("stroke-width", "0.009"); el.setAttribute("class", "home");
      }
      svg.appendChild(el);
      return el;
    });
    view.innerHTML = "";
    view.appendChild(svg);
    svg.addEventListener("pointerdown", function (ev) {
      touches.set(ev.pointerId, [ev.clientX, ev.clientY]);
      if (touches.size === 2) { // a pinch begins: the drag (if any) stops where it is
        start = null; V0 = null; delete root.dataset.dragging;
        const t = Array.from(touches.values());
        pinch = { d: Math.hypot(t[0][0] - t[1][0], t[0][1] - t[1][1]) || 1, zoom: zoom, centre: centre.slice(),
                  mid: svgPoint((t[0][0] + t[1][0]) / 2, (t[0][1] + t[1][1]) / 2) };
        try { svg.setPointerCapture(ev.pointerId); } catch (e) { /* a synthetic pointer */ }
        return;
      }
      if (touches.size > 2) return;
      const p = discPoint(ev);
      if (!inside(p)) return;
      start = p; V0 = V.slice();
      starts.push(p);
      try { svg.setPointerCapture(ev.pointerId); } catch (e) { /* a synthetic pointer */ }
      root.dataset.dragging = "1";
    });
    svg.addEventListener("pointermove", function (ev) {
      if (touches.has(ev.pointerId)) touches.set(ev.pointerId, [ev.clientX, ev.clientY]);
      if (pinch && touches.size === 2) {
        const t = Array.from(touches.values());
        const d = Math.hypot(t[0][0] - t[1][0], t[0][1] - t[1][1]);
        zoomAbout(pinch.mid, pinch.zoom * d / pinch.d, pinch.zoom, pinch.centre);
        root.dataset.renders = String(Number(root.dataset.renders || 0) + 1);
        return;
      }
      if (!start) return;
      let p = discPoint(ev);
      if (hyper && !inside(p)) { const r = Math.hypot(p[0], p[1]) / 0.9999; p = [p[0] / r, p[1] / r]; }
      V = mul(hyper ? translation(start, p) : rotation(sphereAt(start), sphereAt(p)), V0);
      if (hyper) rebaseView();
      later();
    });
    const end = function (ev) {
      touches.delete(ev.pointerId);
      if (touches.size < 2) pinch = null;
      if (!start) return;
      start = null; V0 = null;
      delete root.dataset.dragging;
      later();
    };
    svg.addEventListener("pointerup", end);
    svg.addEventListener("pointercancel", end);
    svg.addEventListener("wheel", function (ev) {
      ev.preventDefault();
      const step = ev.deltaMode === 1 ? 40 : ev.deltaMode === 2 ? 800 : 1; // lines, pages to pixels
      zoomAbout(svgPoint(ev.clientX, ev.clientY), zoom * Math.exp(-ev.deltaY * step * 0.0015), zoom, centre);
      root.dataset.renders = String(Number(root.dataset.renders || 0) + 1);
    }, { passive: false });
  }
  let loads = 0;
  function load() {
    const mine = ++loads, keep = data !== null;
    fetch(root.dataset.src).then(function (r) {
      return r.json().then(function (body) {
        if (!r.ok) throw new Error(body.error || ("HTTP " + r.status));
        return body;
      });
    }).then(function (body) {
      if (mine !== loads) return; // a newer request was sent
      data = body;
      hyper = body.geometry === "hyperbolic";
      syms = [];
      for (let i = 0; hyper && i < body.symmetries.length; i += 9) syms.push(body.symmetries.slice(i, i + 9));
      if (!keep) V = hyper ? eye() : [1, 0, 0, 0, 0.906307787, -0.422618262, 0, 0.422618262, 0.906307787];
      build(keep);
      draw();
      errorBox.textContent = "";
      status.textContent = body.sizes.length + " faces" +
        (hyper ? " within hyperbolic distance " + body.radius.toFixed(2) + " of the patch's centre" : "");
      root.dataset.state = "ok";
      root.dispatchEvent(new CustomEvent("curved-loaded", { detail: body }));
    }).catch(function (err) {
      if (mine !== loads) return;
      errorBox.textContent = String(err.message || err);
      root.dataset.state = "error";
      root.dispatchEvent(new CustomEvent("curved-refused", { detail: String(err.message || err) }));
    });
  }
  root.addEventListener("curved-reload", load);
  // the address bar keeps the page's other parameters and says the view (?view=stereographic)
  function syncUrl() {
    const kept = location.search.replace(/^\?/, "").split("&").filter(function (s) { return s && !/^view=/.test(s); });
    if (stereo) kept.push("view=stereographic");
    history.replaceState(null, "", location.pathname + (kept.length ? "?" + kept.join("&") : "") + location.hash);
  }
  if (choice) choice.addEventListener("change", function () {
    stereo = choice.value === "stereographic";
    root.dataset.projection = choice.value;
    syncUrl();
    if (svg) { zoom = 1; centre = [0, 0]; setBox(); } // the rotation stays; the zoom starts again
    if (data) draw();
  });
  document.getElementById("reset").addEventListener("click", function () {
    V = hyper ? eye() : [1, 0, 0, 0, 0.906307787, -0.422618262, 0, 0.422618262, 0.906307787];
    if (svg) { zoom = 1; centre = [0, 0]; setBox(); }
    if (data) draw();
  });
  load();
})();
