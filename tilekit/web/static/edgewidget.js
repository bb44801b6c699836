// The edge widget of the editors (the planar isohedral editor, the curved tile editor): one
// per shape class, with draggable handles on the fundamental part of the edge (§5.3.1):
// J: the whole edge; U: the first half, mirrored in the perpendicular bisector; S: the first
// half, turned a half turn about the midpoint; I edges have no widget. Double-click the widget
// to add a point, a handle to remove it, or use "add point". A handle stays within x in
// [-0.5, 1.5], y in [-1, 1]; values from a drag are rounded to 4 decimals (screen coordinates
// carry float32 noise). TilekitEdges.widget(label, e, changed) edits e = {kind, smooth,
// points} in place and calls changed() after every change.
(function () {
  "use strict";
  const NS = "http://www.w3.org/2000/svg";
  function snap(x) { return Math.round(x * 1e4) / 1e4; }
  function scaleOf(kind) { return kind === "J" ? 1 : 0.5; }
  function completed(kind, pts) {
    const s = scaleOf(kind);
    const half = pts.map(function (p) { return [s * p[0], s * p[1]]; });
    if (kind === "J" || kind === "I") return half;
    const second = half.map(function (p) { return kind === "U" ? [1 - p[0], p[1]] : [1 - p[0], -p[1]]; }).reverse();
    return half.concat(second.slice(1));
  }

  function widget(label, e, changed) {
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
            const x = snap(Math.min(1.5, Math.max(-0.5, q[0] / s))), y = snap(Math.min(1, Math.max(-1, q[1] / s)));
            e.points[i] = [x, y];
            c.setAttribute("cx", s * x); c.setAttribute("cy", s * y);
            curve.setAttribute("points", completed(e.kind, e.points).map(function (p) { return p[0] + "," + p[1]; }).join(" "));
            changed();
          }
          function up() { c.removeEventListener("pointermove", move); c.removeEventListener("pointerup", up); draw(); }
          c.addEventListener("pointermove", move);
          c.addEventListener("pointerup", up);
        });
        c.addEventListener("dblclick", function (evt) {
          evt.stopPropagation();
          e.points.splice(i, 1); draw(); changed();
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
      e.points.splice(at, 0, [snap(x), snap(y)]); draw(); changed();
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
      e.points.splice(best + 1, 0, [snap((a[0] + b[0]) / 2), snap((a[1] + b[1]) / 2 + 0.15)]);
      draw(); changed();
    });
    wrap.appendChild(add);
    draw();
    return wrap;
  }

  window.TilekitEdges = { widget: widget, completed: completed, snap: snap };
})();
