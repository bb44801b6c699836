// The Penrose quasivertex editor (§6.3, Figure 6.13): r1, theta1, r2, theta2 and the depth of
// the substituted patch; the server builds the deformed rhombs and refuses self-intersecting ones.
(function () {
  "use strict";
  const root = document.getElementById("penrose");
  if (!root) return;
  const view = document.getElementById("view");
  const errorBox = document.getElementById("error");
  const keys = ["r1", "theta1", "r2", "theta2"];
  let timer = null;

  function query(extra) {
    return window.tilekitQuery(function (q) {
      keys.forEach(function (k) { q.set(k, document.getElementById(k).value); });
    }, extra);
  }

  const live = window.tilekitLive(root, view, errorBox);

  function render() {
    live("/api/render/penrose-p3?" + query({ format: "json", size: 720 }));
    document.getElementById("export-svg").href = "/api/render/penrose-p3?" + query({ format: "svg", size: 800, download: 1 });
    const spec = query({ download: 1 });
    document.getElementById("export-spec").href = "/api/tiling/penrose-p3/spec?" + spec;
  }

  keys.concat(["extent"]).forEach(function (k) {
    const input = document.getElementById(k), out = document.getElementById(k + "-out");
    input.addEventListener("input", function () {
      out.textContent = input.value;
      clearTimeout(timer); timer = setTimeout(render, 120);
    });
  });
  render();
})();
