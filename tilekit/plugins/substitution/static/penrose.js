// The Penrose quasivertex editor (§6.3, Figure 6.13 for P3; P2's kite and dart with
// ?tiling=p2, the page's data-system): r1, theta1, r2, theta2 and the depth of
// the substituted patch; the server builds the deformed rhombs and refuses self-intersecting ones.
// The r sliders are limited to the values that keep both rhombs simple for the other three
// parameters (/api/penrose/range, asked again as they change); the export links name the last
// tiling drawn, so a refused setting never exports nothing.
(function () {
  "use strict";
  const root = document.getElementById("penrose");
  if (!root) return;
  const view = document.getElementById("view");
  const errorBox = document.getElementById("error");
  const keys = ["r1", "theta1", "r2", "theta2"];
  const system = root.dataset.system || "penrose-p3";  // penrose-p3 or penrose-p2 (?tiling=p2)
  let timer = null, rangeSeq = 0;

  function query(extra) {
    return window.tilekitQuery(function (q) {
      keys.forEach(function (k) { q.set(k, document.getElementById(k).value); });
    }, extra);
  }

  const live = window.tilekitLive(root, view, errorBox);

  function render() {
    const links = { svg: "/api/render/" + system + "?" + query({ format: "svg", size: 800, download: 1 }),
                    spec: "/api/tiling/" + system + "/spec?" + query({ download: 1 }) };
    live("/api/render/" + system + "?" + query({ format: "json", size: 720 })).then(function (drawn) {
      if (drawn === true) {
        document.getElementById("export-svg").href = links.svg;
        document.getElementById("export-spec").href = links.spec;
      } else if (drawn === false && document.getElementById("export-spec").getAttribute("href") !== "#") {
        errorBox.textContent += " (the exports give the last tiling drawn)";
      }
    });
  }

  // an r slider's bounds follow the admissible range while its value lies inside it (moving
  // the bounds past the value would move the value behind the user's back)
  function ranges() {
    const mine = ++rangeSeq;
    const q = new URLSearchParams();
    keys.forEach(function (k) { q.set(k, document.getElementById(k).value); });
    q.set("tiling", system === "penrose-p2" ? "p2" : "p3");
    fetch("/api/penrose/range?" + q).then(function (r) { return r.ok ? r.json() : null; }).then(function (body) {
      if (!body || mine !== rangeSeq) return;
      ["r1", "r2"].forEach(function (k) {
        const input = document.getElementById(k), v = Number(input.value), span = body[k];
        if (span && v >= span[0] && v <= span[1]) { input.min = String(span[0]); input.max = String(span[1]); }
      });
      root.dataset.ranges = String(Number(root.dataset.ranges || 0) + 1);
    });
  }

  keys.concat(["extent"]).forEach(function (k) {
    const input = document.getElementById(k), out = document.getElementById(k + "-out");
    input.addEventListener("input", function () {
      out.textContent = input.value;
      clearTimeout(timer);
      timer = setTimeout(function () { render(); if (k !== "extent") ranges(); }, 120);
    });
  });
  render();
})();
