// The isohedral editor (exercise 5.12). The server owns the geometry: every change asks
// /api/render for the tiling's SVG (debounced), so the Python engine is the only copy.
// The page opens on the tiling its URL configures (/editor/IHn?params=..&edge=..&colouring=..,
// the API's query syntax, parsed by the server into data-info); data-notice is the one line of
// a URL configuration the server refused (data-info then holds the type's defaults).
// A split tiling (set=split=S,T;PATH, the dihedral tilings of `tilekit escherize GOAL_A GOAL_B`)
// shows the tile with its splitting path: the two ends slide along the boundary, the path's
// points move freely, and the server checks the path stays inside the tile.
// The export links always name the last tiling the server drew (a refused edit keeps them).
(function () {
  "use strict";
  const root = document.getElementById("editor");
  if (!root) return;
  const info = JSON.parse(root.dataset.info);
  const view = document.getElementById("view");
  const errorBox = document.getElementById("error");
  const NS = "http://www.w3.org/2000/svg";
  let state;
  let notice = root.dataset.notice || "";

  // the URL's tiling (defaults = false) or the type's defaults (reset)
  function fresh(defaults) {
    const edges = {};
    info.edges.forEach(function (e) {
      const points = defaults ? [[0, 0], [1, 0]] : e.points.map(function (p) { return p.slice(); });
      edges[e.label] = { kind: e.kind, smooth: defaults ? false : e.smooth, points: points };
    });
    const split = !defaults && info.split ? { ends: info.split.ends.slice(), smooth: info.split.smooth,
      points: info.split.points.map(function (p) { return p.slice(); }) } : null;
    return { params: (defaults ? info.default : info.params).slice(), edges: edges, split: split,
             colouring: defaults ? info.default_colouring : info.colouring, palette: "",
             zoom: 1, rotate: 0, cx: (info.region[0] + info.region[2]) / 2, cy: (info.region[1] + info.region[3]) / 2 };
  }

  // fmt rounds for display and the view region; num is exact (the shortest text that reads
  // back as the same double in Python), so params and edges survive a link or an export
  function fmt(x) { return (Math.round(x * 1e6) / 1e6).toString(); }
  function num(x) { return String(x); }
  // a value a drag produced, to 4 decimals (screen coordinates carry float32 noise that would
  // otherwise reach the URL and the exported spec as 0.30000001192092896)
  function snap(x) { return Math.round(x * 1e4) / 1e4; }

  function splitText() {
    const sp = state.split;
    return num(sp.ends[0]) + "," + num(sp.ends[1]) + ";" + (sp.smooth ? "bezier:" : "") +
      sp.points.map(function (p) { return num(p[0]) + "," + num(p[1]); }).join(":");
  }

  function edgeText(label) {
    const e = state.edges[label];
    return label + "=" + (e.smooth ? "bezier:" : "") + e.points.map(function (p) { return num(p[0]) + "," + num(p[1]); }).join(":");
  }

  // the tiling's own options: params, the shaped edges, a colouring other than the type's
  function tilingQuery() {
    const q = new URLSearchParams();
    if (state.params.length) q.set("params", state.params.map(num).join(","));
    Object.keys(state.edges).forEach(function (label) {
      const e = state.edges[label];
      if (e.points.length > 2 || e.points.some(function (p) { return p[1] !== 0; })) q.append("edge", edgeText(label));
    });
    if (state.colouring && state.colouring !== info.default_colouring) q.set("colouring", state.colouring);
    if (state.split) q.append("set", "split=" + splitText());
    return q;
  }

  // /editor/IHn?...: the link's form, with the edge syntax's , : = left readable (and no
  // params while they are the type's defaults)
  function editorLink() {
    const parts = [];
    const q = tilingQuery();
    if (state.params.every(function (v, i) { return v === info.default[i]; })) q.delete("params");
    q.forEach(function (value, key) {
      parts.push(key + "=" + encodeURIComponent(value).replace(/%2C/g, ",").replace(/%3A/g, ":").replace(/%3D/g, "=")
        .replace(/%3B/g, ";"));
    });
    return "/editor/" + encodeURIComponent(info.name) + (parts.length ? "?" + parts.join("&") : "");
  }

  // a rotated square view of side 1 needs a square of side |cos| + |sin| behind it: the picture
  // is drawn that much larger (region and pixels) so no corner of the view is left blank
  function cover() {
    const a = state.rotate * Math.PI / 180;
    return Math.abs(Math.cos(a)) + Math.abs(Math.sin(a));
  }

  function query(extra, covered) {
    const q = tilingQuery();
    if (state.palette) q.set("colours", state.palette);
    const k = covered ? cover() : 1;
    const hw = k * (info.region[2] - info.region[0]) / 2 / state.zoom;
    const hh = k * (info.region[3] - info.region[1]) / 2 / state.zoom;
    q.set("region", [state.cx - hw, state.cy - hh, state.cx + hw, state.cy + hh].map(fmt).join(","));
    Object.keys(extra || {}).forEach(function (k) { q.set(k, extra[k]); });
    return q;
  }

  let timer = null, seq = 0;
  function schedule() {
    clearTimeout(timer);
    timer = setTimeout(render, 120);
  }

  function tileQuery() {
    const q = tilingQuery();
    q.delete("set");
    q.delete("colouring");
    return q.toString();
  }

  let tileKey = null;
  // the tile's outline for the split panel, fetched again when params or edges changed it
  function refreshTile() {
    const key = tileQuery();
    if (key === tileKey) { drawSplit(); return; }
    fetch("/api/tiling/" + encodeURIComponent(info.name) + "/editor?" + key)
      .then(function (r) { return r.ok ? r.json() : null; })
      .then(function (body) {
        if (!body) return;
        tileKey = key;
        info.tile = body.tile;
        drawSplit();
      });
  }

  function render() {
    const mine = ++seq;
    const link = editorLink();
    const exports = exportLinks();  // of the state this render draws
    const k = cover();
    root.dataset.busy = "1";
    fetch("/api/render/" + encodeURIComponent(info.name) + "?" + query({ format: "json", size: Math.round(720 * k) }, true))
      .then(function (r) { return r.json().then(function (body) { return { ok: r.ok, body: body }; }); })
      .then(function (res) {
        if (mine !== seq) return;
        if (!res.ok) {
          errorBox.textContent = (res.body.error || "render failed") +
            (root.dataset.state === "ok" ? " (the exports give the last tiling drawn)" : "");
          notice = "";
          root.dataset.state = "refused";
        } else {
          errorBox.textContent = notice;  // a refused URL's line stays until the next valid render
          notice = "";
          view.innerHTML = res.body.svg;  // tilekit's own SVG: numbers and escaped colours only
          const svg = view.querySelector("svg");
          if (svg) {
            svg.removeAttribute("width"); svg.removeAttribute("height");
            placeSvg(svg, k);
          }
          root.dataset.state = "ok";
          root.dataset.spec = JSON.stringify(res.body.spec);
          applyExports(exports);
          refreshTile();
          // the link and the address bar name the tiling on screen (the last valid one)
          document.getElementById("permalink").href = link;
          if (window.location.pathname + window.location.search !== link) window.history.replaceState(null, "", link);
        }
        root.dataset.renders = String(Number(root.dataset.renders || 0) + 1);
        delete root.dataset.busy;
      })
      .catch(function (err) { if (mine === seq) { errorBox.textContent = String(err); delete root.dataset.busy; } });
  }

  // the picture, k times the view's size, centred in it and turned by the rotate slider
  function placeSvg(svg, k) {
    // patch_to_svg pads the region by 2% of its size on each side (a margin and a frame):
    // the view box is cut back to the region so the picture fills the view edge to edge
    const vb = (svg.getAttribute("viewBox") || "").split(/[ ,]+/).map(Number);
    if (vb.length === 4 && vb.every(isFinite)) {
      const w = vb[2] / 1.04, h = vb[3] / 1.04, pad = 0.02 * Math.max(w, h);
      svg.setAttribute("viewBox", [vb[0] + pad, vb[1] + pad, w, h].join(" "));
    }
    svg.style.width = svg.style.height = (100 * k) + "%";
    svg.style.marginLeft = svg.style.marginTop = (-50 * (k - 1)) + "%";
    svg.style.transform = "rotate(" + state.rotate + "deg)";
  }

  function exportLinks() {
    const q = query({ download: 1 }); q.delete("region"); q.delete("colours");
    return { svg: "/api/render/" + encodeURIComponent(info.name) + "?" + query({ format: "svg", size: 800, download: 1 }),
             spec: "/api/tiling/" + encodeURIComponent(info.name) + "/spec?" + q };
  }

  function applyExports(links) {
    const svgLink = document.getElementById("export-svg");
    svgLink.href = links.svg;
    svgLink.download = info.name + ".svg";
    const specLink = document.getElementById("export-spec");
    specLink.href = links.spec;
    specLink.download = info.name + ".json";
  }

  // -- tiling vertex parameters: one slider each
  function buildParams() {
    const box = document.getElementById("params");
    box.textContent = "";
    if (!state.params.length) { box.textContent = "this type has no free parameters"; return; }
    state.params.forEach(function (v, i) {
      const d = info.default[i];
      const span = Math.max(0.5 * Math.abs(d), 0.25);
      const label = document.createElement("label");
      label.textContent = "v" + i + " ";
      const input = document.createElement("input");
      input.type = "range"; input.id = "param-" + i; input.className = "param";
      // around the default, widened to take the URL's value; step "any" keeps it exact
      input.min = num(Math.min(d - span, v)); input.max = num(Math.max(d + span, v)); input.step = "any";
      input.value = num(v);
      const out = document.createElement("output");
      out.textContent = fmt(v);
      input.addEventListener("input", function () {
        state.params[i] = snap(Number(input.value)); out.textContent = fmt(state.params[i]); schedule();
      });
      label.appendChild(input); label.appendChild(out); box.appendChild(label);
    });
  }

  // -- edge shapes: a widget per shape class (TilekitEdges, /static/edgewidget.js)
  function buildEdges() {
    const box = document.getElementById("edges");
    box.textContent = "";
    if (!info.edges.length) { box.textContent = "every edge of this type is an I edge (straight)"; return; }
    info.edges.forEach(function (e) { box.appendChild(TilekitEdges.widget(e.label, state.edges[e.label], schedule)); });
  }

  // -- view: zoom and rotate sliders, drag to pan, wheel to zoom
  function wireView() {
    const zoom = document.getElementById("zoom"), rotate = document.getElementById("rotate");
    zoom.addEventListener("input", function () { state.zoom = Number(zoom.value); schedule(); });
    rotate.addEventListener("input", function () {
      state.rotate = Number(rotate.value);
      const svg = view.querySelector("svg");
      if (svg) svg.style.transform = "rotate(" + state.rotate + "deg)";
      schedule();  // a larger square behind the turned view
    });
    view.addEventListener("wheel", function (evt) {
      evt.preventDefault();
      state.zoom = Math.min(3, Math.max(0.3, state.zoom * (evt.deltaY < 0 ? 1.1 : 1 / 1.1)));
      zoom.value = String(state.zoom); schedule();
    }, { passive: false });
    let drag = null;
    view.addEventListener("pointerdown", function (evt) { drag = [evt.clientX, evt.clientY]; view.setPointerCapture(evt.pointerId); });
    view.addEventListener("pointermove", function (evt) {
      if (!drag) return;
      const w = view.getBoundingClientRect().width || 1;
      const units = (info.region[2] - info.region[0]) / state.zoom / w;
      const a = -state.rotate * Math.PI / 180;
      const dx = (evt.clientX - drag[0]) * units, dy = (evt.clientY - drag[1]) * units;
      state.cx -= dx * Math.cos(a) + dy * Math.sin(a);
      state.cy += -dx * Math.sin(a) + dy * Math.cos(a);
      drag = [evt.clientX, evt.clientY];
      schedule();
    });
    view.addEventListener("pointerup", function () { drag = null; });
    document.getElementById("palette").addEventListener("change", function (evt) { state.palette = evt.target.value; schedule(); });
    document.getElementById("colouring").addEventListener("change", function (evt) { state.colouring = evt.target.value.trim(); schedule(); });
    document.getElementById("type").addEventListener("change", function (evt) {
      window.location.href = "/editor/" + encodeURIComponent(evt.target.value);
    });
    document.getElementById("reset").addEventListener("click", function () {
      state = fresh(true); zoom.value = "1"; rotate.value = "0";
      document.getElementById("colouring").value = state.colouring;
      buildParams(); buildEdges(); drawSplit(); schedule();
    });
    const parquet = document.getElementById("export-parquet");
    if (info.parquet) {
      parquet.hidden = false;
      parquet.addEventListener("click", function () {
        const q = new URLSearchParams({ columns: 12, rows: 4, download: 1 });
        Object.keys(state.edges).forEach(function (label) { q.append("edge", edgeText(label)); });
        if (state.palette) q.set("colours", state.palette);
        parquet.href = "/api/parquet/" + encodeURIComponent(info.name) + "?" + q;
      });
    }
  }

  // -- the split (dihedral tilings): the tile, its two pieces and the splitting path
  // A boundary position s is edge floor(s), a fraction s - floor(s) along its outline segments
  // (tilekit.plugins.isohedral.split); path points are in the frame of the chord between the ends.
  function firsts(counts) {
    const out = [0];
    counts.forEach(function (c) { out.push(out[out.length - 1] + c); });
    return out;
  }
  function outlineAt(w) {
    const P = info.tile.outline, m = P.length;
    const i = ((Math.floor(w) % m) + m) % m, f = w - Math.floor(w), j = (i + 1) % m;
    return [(1 - f) * P[i][0] + f * P[j][0], (1 - f) * P[i][1] + f * P[j][1]];
  }
  function vertexIndex(s) {
    const c = info.tile.counts, first = firsts(c);
    const e = Math.min(Math.floor(s), c.length - 1);
    return first[e] + (s - e) * c[e];
  }
  function boundaryPosition(w) {
    const c = info.tile.counts, first = firsts(c);
    let e = 0;
    while (e + 1 < c.length && first[e + 1] <= w) e++;
    return e + (w - first[e]) / c[e];
  }
  // the boundary position nearest a point (its projection on the outline)
  function project(p) {
    const P = info.tile.outline, m = P.length;
    let best = Infinity, where = 0;
    for (let i = 0; i < m; i++) {
      const a = P[i], b = P[(i + 1) % m];
      const dx = b[0] - a[0], dy = b[1] - a[1], len = dx * dx + dy * dy || 1;
      const f = Math.min(1, Math.max(0, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len));
      const x = a[0] + f * dx - p[0], y = a[1] + f * dy - p[1];
      if (x * x + y * y < best) { best = x * x + y * y; where = i + f; }
    }
    let s = snap(boundaryPosition(where));
    if (s >= info.tile.counts.length) s = 0;
    return s;
  }
  function chord() {
    return [outlineAt(vertexIndex(state.split.ends[0])), outlineAt(vertexIndex(state.split.ends[1]))];
  }
  function toWorld(p) {
    const c = chord(), dx = c[1][0] - c[0][0], dy = c[1][1] - c[0][1];
    return [c[0][0] + p[0] * dx - p[1] * dy, c[0][1] + p[0] * dy + p[1] * dx];
  }
  function toChord(q) {
    const c = chord(), dx = c[1][0] - c[0][0], dy = c[1][1] - c[0][1], n = dx * dx + dy * dy || 1;
    const x = q[0] - c[0][0], y = q[1] - c[0][1];
    return [snap((x * dx + y * dy) / n), snap((y * dx - x * dy) / n)];
  }
  // piece 0: the boundary from end 0 to end 1 counter-clockwise, then the path back
  function pieces() {
    const m = info.tile.outline.length;
    const u = vertexIndex(state.split.ends[0]), v = vertexIndex(state.split.ends[1]);
    const path = state.split.points.slice(1, -1).map(toWorld);
    function between(a, b) {
      const span = ((b - a) % m + m) % m, out = [];
      for (let i = Math.floor(a) + 1; i <= Math.ceil(a + span) - 1; i++) out.push(info.tile.outline[i % m]);
      return out;
    }
    const pu = outlineAt(u), pv = outlineAt(v);
    return [[pu].concat(between(u, v), [pv], path.slice().reverse()), [pv].concat(between(v, u), [pu], path)];
  }

  const splitSvg = document.getElementById("split-svg");
  const splitG = splitSvg.querySelector("g");
  function splitLocal(evt) {
    const pt = splitSvg.createSVGPoint();
    pt.x = evt.clientX; pt.y = evt.clientY;
    const p = pt.matrixTransform(splitG.getScreenCTM().inverse());
    return [p.x, p.y];
  }
  function el(name, attrs) {
    const node = document.createElementNS(NS, name);
    Object.keys(attrs).forEach(function (k) { node.setAttribute(k, attrs[k]); });
    splitG.appendChild(node);
    return node;
  }
  function pts(list) { return list.map(function (p) { return p[0] + "," + p[1]; }).join(" "); }

  function drawSplit() {
    const on = !!state.split;
    document.getElementById("split-add").hidden = on;
    document.getElementById("split-remove").hidden = !on;
    document.getElementById("split-point").hidden = !on;
    splitSvg.hidden = !on;
    // a split tiling is coloured by piece (0 and 1), not by the type's colouring
    const colouring = document.getElementById("colouring");
    colouring.disabled = on;
    colouring.title = on ? "a split tiling is coloured by piece" : "";
    document.getElementById("split-text").textContent = on ? "split=" + splitText() : "";
    splitG.textContent = "";
    if (!on || !info.tile) return;
    const P = info.tile.outline;
    let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
    P.forEach(function (p) { x0 = Math.min(x0, p[0]); x1 = Math.max(x1, p[0]); y0 = Math.min(y0, p[1]); y1 = Math.max(y1, p[1]); });
    const size = Math.max(x1 - x0, y1 - y0), pad = 0.08 * size;
    splitSvg.setAttribute("viewBox", [x0 - pad, -(y1 + pad), x1 - x0 + 2 * pad, y1 - y0 + 2 * pad].join(" "));
    const r = 0.025 * size, w = 0.006 * size;
    pieces().forEach(function (q, i) {
      el("polygon", { points: pts(q), class: "piece piece-" + i, fill: info.piece_colours[i], "stroke-width": w });
    });
    const path = [chord()[0]].concat(state.split.points.slice(1, -1).map(toWorld), [chord()[1]]);
    el("polyline", { points: pts(path), class: "split-path", "stroke-width": 2 * w });
    state.split.ends.forEach(function (s, i) {
      const p = outlineAt(vertexIndex(s));
      handle(el("circle", { cx: p[0], cy: p[1], r: 1.3 * r, class: "handle split-end", "data-index": i, "stroke-width": w }), function (q) {
        const t = project(q);
        if (t !== state.split.ends[1 - i]) state.split.ends[i] = t;
      });
    });
    state.split.points.forEach(function (p, i) {
      if (i === 0 || i === state.split.points.length - 1) return;
      const wpt = toWorld(p);
      const c = el("circle", { cx: wpt[0], cy: wpt[1], r: r, class: "handle split-point", "data-index": i, "stroke-width": w });
      handle(c, function (q) { state.split.points[i] = toChord(q); });
      c.addEventListener("dblclick", function (evt) {
        evt.stopPropagation();
        state.split.points.splice(i, 1); drawSplit(); schedule();
      });
    });
  }

  function handle(node, moveTo) {
    node.addEventListener("pointerdown", function (evt) {
      evt.preventDefault();
      node.setPointerCapture(evt.pointerId);
      function move(ev) { moveTo(splitLocal(ev)); drawSplitLive(); schedule(); }
      function up() { node.removeEventListener("pointermove", move); node.removeEventListener("pointerup", up); drawSplit(); }
      node.addEventListener("pointermove", move);
      node.addEventListener("pointerup", up);
    });
  }
  // while dragging, redraw everything but keep the dragged node (its pointer capture)
  function drawSplitLive() {
    const pieceNodes = splitG.querySelectorAll(".piece");
    const q = pieces();
    pieceNodes.forEach(function (n, i) { n.setAttribute("points", pts(q[i])); });
    const path = [chord()[0]].concat(state.split.points.slice(1, -1).map(toWorld), [chord()[1]]);
    splitG.querySelector(".split-path").setAttribute("points", pts(path));
    splitG.querySelectorAll(".split-end").forEach(function (n) {
      const p = outlineAt(vertexIndex(state.split.ends[Number(n.dataset.index)]));
      n.setAttribute("cx", p[0]); n.setAttribute("cy", p[1]);
    });
    splitG.querySelectorAll(".split-point").forEach(function (n) {
      const p = toWorld(state.split.points[Number(n.dataset.index)]);
      n.setAttribute("cx", p[0]); n.setAttribute("cy", p[1]);
    });
    document.getElementById("split-text").textContent = "split=" + splitText();
  }

  function wireSplit() {
    document.getElementById("split-add").addEventListener("click", function () {
      const n = info.tile.counts.length;
      state.split = { ends: [0.5, Math.floor(n / 2) + 0.5], points: [[0, 0], [1, 0]], smooth: false };
      drawSplit(); schedule();
    });
    document.getElementById("split-remove").addEventListener("click", function () {
      state.split = null; drawSplit(); schedule();
    });
    document.getElementById("split-point").addEventListener("click", function () {
      const p = state.split.points;
      let best = 0, len = -1;
      for (let k = 0; k + 1 < p.length; k++) {
        const dx = p[k + 1][0] - p[k][0], dy = p[k + 1][1] - p[k][1];
        if (dx * dx + dy * dy > len) { len = dx * dx + dy * dy; best = k; }
      }
      p.splice(best + 1, 0, [snap((p[best][0] + p[best + 1][0]) / 2), snap((p[best][1] + p[best + 1][1]) / 2 + 0.1)]);
      drawSplit(); schedule();
    });
  }

  state = fresh(false);
  buildParams();
  buildEdges();
  wireView();
  wireSplit();
  drawSplit();
  schedule();
})();
