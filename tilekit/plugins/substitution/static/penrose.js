// The Penrose quasivertex editor (§6.3, Figure 6.13): r1, theta1, r2, theta2 and the depth of
// the substituted patch; the server builds the deformed rhombs and refuses self-intersecting ones.
(function () {
  "use strict";
  const root = document.getElementById("penrose");
  if (!root) return;
  const view = document.getElementById("view");
  const errorBox = document.getElementById("error");
  const keys = ["r1", "theta1", "r2", "theta2"];
  let timer = null, seq = 0;

  function query(extra) {
    const q = new URLSearchParams();
    keys.forEach(function (k) { q.set(k, document.getElementById(k).value); });
    const e = Number(document.getElementById("extent").value);
    q.set("region", [-e, -e, e, e].join(","));
    Object.keys(extra || {}).forEach(function (k) { q.set(k, extra[k]); });
    return q;
  }

  function render() {
    const mine = ++seq;
    fetch("/api/render/penrose-p3?" + query({ format: "json", size: 720 }))
      .then(function (r) { return r.json().then(function (b) { return { ok: r.ok, body: b }; }); })
      .then(function (res) {
        if (mine !== seq) return;
        if (!res.ok) {
          errorBox.textContent = res.body.error || "render failed";
          root.dataset.state = "refused";
          return;
        }
        errorBox.textContent = "";
        view.innerHTML = res.body.svg;
        const svg = view.querySelector("svg");
        if (svg) { svg.removeAttribute("width"); svg.removeAttribute("height"); }
        root.dataset.state = "ok";
        root.dataset.renders = String(Number(root.dataset.renders || 0) + 1);
      });
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
