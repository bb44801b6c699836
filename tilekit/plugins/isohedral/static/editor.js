// The isohedral editor (exercise 5.12). The server owns the geometry: every change asks
// /api/render for the tiling's SVG (debounced), so the Python engine is the only copy.
// The page opens on the tiling its URL configures (/editor/IHn?params=..&edge=..&colouring=..,
// the API's query syntax, parsed by the server into data-info); data-notice is the one line of
// a URL configuration the server refused (data-info then holds the type's defaults).
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
    return { params: (defaults ? info.default : info.params).slice(), edges: edges,
             colouring: defaults ? info.default_colouring : info.colouring, palette: "",
             zoom: 1, rotate: 0, cx: (info.region[0] + info.region[2]) / 2, cy: (info.region[1] + info.region[3]) / 2 };
  }

  // fmt rounds for display and the view region; num is exact (the shortest text that reads
  // back as the same double in Python), so params and edges survive a link or an export
  function fmt(x) { return (Math.round(x * 1e6) / 1e6).toString(); }
  function num(x) { return String(x); }

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
    return q;
  }

  // /editor/IHn?...: the link's form, with the edge syntax's , : = left readable (and no
  // params while they are the type's defaults)
  function editorLink() {
    const parts = [];
    const q = tilingQuery();
    if (state.params.every(function (v, i) { return v === info.default[i]; })) q.delete("params");
    q.forEach(function (value, key) {
      parts.push(key + "=" + encodeURIComponent(value).replace(/%2C/g, ",").replace(/%3A/g, ":").replace(/%3D/g, "="));
    });
    return "/editor/" + encodeURIComponent(info.name) + (parts.length ? "?" + parts.join("&") : "");
  }

  function query(extra) {
    const q = tilingQuery();
    if (state.palette) q.set("colours", state.palette);
    const hw = (info.region[2] - info.region[0]) / 2 / state.zoom;
    const hh = (info.region[3] - info.region[1]) / 2 / state.zoom;
    q.set("region", [state.cx - hw, state.cy - hh, state.cx + hw, state.cy + hh].map(fmt).join(","));
    Object.keys(extra || {}).forEach(function (k) { q.set(k, extra[k]); });
    return q;
  }

  let timer = null, seq = 0;
  function schedule() {
    clearTimeout(timer);
    timer = setTimeout(render, 120);
    updateExports();
  }

  function render() {
    const mine = ++seq;
    const link = editorLink();
    root.dataset.busy = "1";
    fetch("/api/render/" + encodeURIComponent(info.name) + "?" + query({ format: "json", size: 720 }))
      .then(function (r) { return r.json().then(function (body) { return { ok: r.ok, body: body }; }); })
      .then(function (res) {
        if (mine !== seq) return;
        if (!res.ok) {
          errorBox.textContent = res.body.error || "render failed";
          notice = "";
          root.dataset.state = "refused";
        } else {
          errorBox.textContent = notice;  // a refused URL's line stays until the next valid render
          notice = "";
          view.innerHTML = res.body.svg;  // tilekit's own SVG: numbers and escaped colours only
          const svg = view.querySelector("svg");
          if (svg) {
            svg.removeAttribute("width"); svg.removeAttribute("height");
            svg.style.transform = "rotate(" + state.rotate + "deg)";
          }
          root.dataset.state = "ok";
          root.dataset.spec = JSON.stringify(res.body.spec);
          // the link and the address bar name the tiling on screen (the last valid one)
          document.getElementById("permalink").href = link;
          if (window.location.pathname + window.location.search !== link) window.history.replaceState(null, "", link);
        }
        root.dataset.renders = String(Number(root.dataset.renders || 0) + 1);
        delete root.dataset.busy;
      })
      .catch(function (err) { if (mine === seq) { errorBox.textContent = String(err); delete root.dataset.busy; } });
  }

  function updateExports() {
    const svgLink = document.getElementById("export-svg");
    svgLink.href = "/api/render/" + encodeURIComponent(info.name) + "?" + query({ format: "svg", size: 800, download: 1 });
    svgLink.download = info.name + ".svg";
    const specLink = document.getElementById("export-spec");
    const q = query({ download: 1 }); q.delete("region"); q.delete("colours");
    specLink.href = "/api/tiling/" + encodeURIComponent(info.name) + "/spec?" + q;
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
        state.params[i] = Number(input.value); out.textContent = fmt(state.params[i]); schedule();
      });
      label.appendChild(input); label.appendChild(out); box.appendChild(label);
    });
  }

  // -- edge shapes: a widget per shape class, handles on the fundamental part.
  // J: the whole edge; U: the first half, mirrored in the perpendicular bisector;
  // S: the first half, turned a half turn about the midpoint; I: straight, no handles.
  function scaleOf(kind) { return kind === "J" ? 1 : 0.5; }
  function completed(kind, pts) {
    const s = scaleOf(kind);
    const half = pts.map(function (p) { return [s * p[0], s * p[1]]; });
    if (kind === "J" || kind === "I") return half;
    const second = half.map(function (p) { return kind === "U" ? [1 - p[0], p[1]] : [1 - p[0], -p[1]]; }).reverse();
    return half.concat(second.slice(1));
  }

  function buildEdges() {
    const box = document.getElementById("edges");
    box.textContent = "";
    if (!info.edges.length) { box.textContent = "every edge of this type is an I edge (straight)"; return; }
    info.edges.forEach(function (e) { box.appendChild(edgeWidget(e.label)); });
  }

  function edgeWidget(label) {
    const e = state.edges[label];
    const wrap = document.createElement("div");
    wrap.className = "edge";
    const title = document.createElement("div");
    title.textContent = "edge " + label + " (" + e.kind + ")";
    wrap.appendChild(title);
    const svg = document.createElementNS(NS, "svg");
    svg.setAttribute("viewBox", "-0.1 -0.55 1.2 1.1");
    svg.setAttribute("class", "edge-svg");
    svg.id = "edge-" + label;
    const g = document.createElementNS(NS, "g");
    g.setAttribute("transform", "scale(1,-1)");
    svg.appendChild(g);
    wrap.appendChild(svg);

    function toLocal(evt) {
      const pt = svg.createSVGPoint();
      pt.x = evt.clientX; pt.y = evt.clientY;
      const p = pt.matrixTransform(g.getScreenCTM().inverse());
      return [p.x, p.y];
    }

    function draw() {
      g.textContent = "";
      const base = document.createElementNS(NS, "line");
      base.setAttribute("x1", "0"); base.setAttribute("y1", "0"); base.setAttribute("x2", "1"); base.setAttribute("y2", "0");
      base.setAttribute("class", "base");
      g.appendChild(base);
      const curve = document.createElementNS(NS, "polyline");
      curve.setAttribute("points", completed(e.kind, e.points).map(function (p) { return p[0] + "," + p[1]; }).join(" "));
      curve.setAttribute("class", "curve");
      g.appendChild(curve);
      const s = scaleOf(e.kind);
      e.points.forEach(function (p, i) {
        if (i === 0 || i === e.points.length - 1) return;
        const c = document.createElementNS(NS, "circle");
        c.setAttribute("cx", s * p[0]); c.setAttribute("cy", s * p[1]); c.setAttribute("r", "0.035");
        c.setAttribute("class", "handle"); c.dataset.index = String(i);
        c.addEventListener("pointerdown", function (evt) {
          evt.preventDefault();
          c.setPointerCapture(evt.pointerId);
          function move(ev) {
            const q = toLocal(ev);
            const x = Math.min(1.5, Math.max(-0.5, q[0] / s)), y = Math.min(1, Math.max(-1, q[1] / s));
            e.points[i] = [x, y];
            c.setAttribute("cx", s * x); c.setAttribute("cy", s * y);
            curve.setAttribute("points", completed(e.kind, e.points).map(function (p) { return p[0] + "," + p[1]; }).join(" "));
            schedule();
          }
          function up() { c.removeEventListener("pointermove", move); c.removeEventListener("pointerup", up); draw(); }
          c.addEventListener("pointermove", move);
          c.addEventListener("pointerup", up);
        });
        c.addEventListener("dblclick", function (evt) {
          evt.stopPropagation();
          e.points.splice(i, 1); draw(); schedule();
        });
        g.appendChild(c);
      });
    }

    svg.addEventListener("dblclick", function (evt) {
      const q = toLocal(evt), s = scaleOf(e.kind);
      const x = q[0] / s, y = q[1] / s;
      if (e.smooth || x <= 0 || x >= 1) return;
      let at = e.points.length - 1;
      for (let k = 1; k < e.points.length; k++) { if (e.points[k][0] > x) { at = k; break; } }
      e.points.splice(at, 0, [x, y]); draw(); schedule();
    });
    const add = document.createElement("button");
    add.type = "button"; add.textContent = "add point"; add.className = "add-point";
    add.addEventListener("click", function () {
      if (e.smooth) return;
      let best = 0, len = -1;
      for (let k = 0; k + 1 < e.points.length; k++) {
        const dx = e.points[k + 1][0] - e.points[k][0], dy = e.points[k + 1][1] - e.points[k][1];
        if (dx * dx + dy * dy > len) { len = dx * dx + dy * dy; best = k; }
      }
      const a = e.points[best], b = e.points[best + 1];
      e.points.splice(best + 1, 0, [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2 + 0.15]);
      draw(); schedule();
    });
    wrap.appendChild(add);
    draw();
    return wrap;
  }

  // -- view: zoom and rotate sliders, drag to pan, wheel to zoom
  function wireView() {
    const zoom = document.getElementById("zoom"), rotate = document.getElementById("rotate");
    zoom.addEventListener("input", function () { state.zoom = Number(zoom.value); schedule(); });
    rotate.addEventListener("input", function () {
      state.rotate = Number(rotate.value);
      const svg = view.querySelector("svg");
      if (svg) svg.style.transform = "rotate(" + state.rotate + "deg)";
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
      buildParams(); buildEdges(); schedule();
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

  state = fresh(false);
  buildParams();
  buildEdges();
  wireView();
  schedule();
})();
