// The curved tile editor (tilekit/plugins/curved/web.py, /curved/edit/NAME): one edge widget
// per shape class (TilekitEdges, /static/edgewidget.js, the planar editor's), the tiling drawn
// by the viewer (viewer.js). Every change (debounced by 120 ms) points the viewer at
// /api/curved/edit/NAME?edge=LABEL=SHAPE&... and asks it to reload: the server builds the
// tiling through the family's edges option, so the geometry exists once, in Python. A refused
// edit shows the API's one line under the controls and the last valid tiling stays on screen,
// with its link, SVG export and command line; the address bar follows the last tiling drawn.
(function () {
  "use strict";
  const root = document.getElementById("curved");
  if (!root || !root.dataset.info) return;
  const info = JSON.parse(root.dataset.info);
  const api = "/api/curved/edit/" + encodeURIComponent(info.name);
  const notice = document.getElementById("notice");
  let edges = {}, timer = null, rebuild = false, first = true;

  function fresh(list) {
    edges = {};
    list.forEach(function (e) {
      edges[e.label] = { kind: e.kind, smooth: e.smooth, points: e.points.map(function (p) { return p.slice(); }) };
    });
    const box = document.getElementById("edges");
    box.textContent = "";
    list.forEach(function (e) {
      const w = TilekitEdges.widget(e.label, edges[e.label], schedule);
      if (e.tile_edges) {
        const which = document.createElement("div");
        which.className = "note";
        which.textContent = "the tile's edges " + e.tile_edges.join(", ");
        w.appendChild(which);
      }
      box.appendChild(w);
    });
  }

  // the shapes at full precision (the shortest text that reads back as the same double)
  function query() {
    return Object.keys(edges).map(function (label) {
      const e = edges[label];
      return "edge=" + encodeURIComponent(label + "=" + (e.smooth ? "bezier:" : "") +
        e.points.map(function (p) { return String(p[0]) + "," + String(p[1]); }).join(":"))
        .replace(/%2C/g, ",").replace(/%3A/g, ":").replace(/%3D/g, "=");
    }).join("&");
  }

  function reload(src) {
    root.dataset.src = src;
    root.dataset.busy = "1";
    root.dispatchEvent(new CustomEvent("curved-reload"));
  }
  function schedule() {
    clearTimeout(timer);
    timer = setTimeout(function () { reload(api + "?" + query()); }, 120);
  }

  root.addEventListener("curved-loaded", function (ev) {
    const body = ev.detail;
    delete root.dataset.busy;
    if (!first) notice.textContent = ""; // the page's own notice (a refused URL) stays until an edit is drawn
    first = false;
    if (rebuild) { rebuild = false; fresh(body.edges); }
    document.getElementById("link").href = body.link;
    document.getElementById("svg").href = body.svg;
    document.getElementById("cli").textContent = body.cli;
    root.dataset.query = body.query.join("&");
    // the address bar also keeps the page's view (viewer.js's ?view=), which the link leaves out
    history.replaceState(null, "", body.link + (root.dataset.projection === "stereographic" ? "&view=stereographic" : ""));
  });
  root.addEventListener("curved-refused", function (ev) {
    delete root.dataset.busy;
    notice.textContent = ev.detail + " (the last valid tiling stays on screen)";
    document.getElementById("error").textContent = ""; // said once, here
  });
  document.getElementById("defaults").addEventListener("click", function () {
    rebuild = true;
    reload(api);
  });
  fresh(info.edges);
})();
