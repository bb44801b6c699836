// Live progress of a search run: server-sent events from /api/runs/ID/events.
(function () {
  "use strict";
  const root = document.getElementById("run");
  if (!root) return;
  const id = root.dataset.run;
  const terminal = ["done", "failed", "cancelled", "interrupted"];
  // the page's formats (tilekit/web/pages.py: duration, fmt_number)
  function duration(t) {
    if (!(t >= 0)) return "\u2014";
    if (t < 1) return t.toPrecision(2) + " s";
    if (t < 10) return t.toFixed(1) + " s";
    if (t < 60) return Math.round(t) + " s";
    if (t < 3600) return Math.floor(t / 60) + " min " + String(Math.floor(t % 60)).padStart(2, "0") + " s";
    return Math.floor(t / 3600) + " h " + String(Math.floor(t % 3600 / 60)).padStart(2, "0") + " min";
  }
  function count(x) { return Number(x).toLocaleString("en-US", { maximumSignificantDigits: 4 }); }
  function show(info) {
    const done = Number(info.chunks_done), total = Math.max(1, Number(info.chunks_total));
    const seconds = Number(info.seconds) || 0;
    document.getElementById("status").textContent = info.status;
    document.getElementById("chunks").textContent = done.toLocaleString("en-US") + "/" +
      Number(info.chunks_total).toLocaleString("en-US");
    document.getElementById("rows").textContent = Number(info.rows).toLocaleString("en-US");
    document.getElementById("seconds").textContent = duration(seconds);
    if (seconds > 0) {
      document.getElementById("rate").textContent = count(info.rows / seconds) + " rows/s, " +
        count(done / seconds) + " chunks/s";
    }
    const running = terminal.indexOf(info.status) < 0;
    document.getElementById("eta").textContent = !running ? "\u2014" :
      (done > 0 && seconds > 0 ? duration((total - done) * seconds / done) : "\u2014");
    document.getElementById("progress").value = 100 * done / total;
    document.getElementById("percent").textContent = Math.round(100 * done / total) + "%";
    root.dataset.status = info.status;
  }
  if (terminal.indexOf(root.dataset.status) < 0 && window.EventSource) {
    const source = new EventSource("/api/runs/" + encodeURIComponent(id) + "/events");
    const started = root.dataset.status;
    source.addEventListener("progress", function (evt) { show(JSON.parse(evt.data)); });
    source.addEventListener("end", function (evt) {
      show(JSON.parse(evt.data)); source.close();
      if (started !== "done") window.location.reload();  // the results table is complete now
    });
    source.addEventListener("timeout", function () { source.close(); });
  }
  const cancel = document.getElementById("cancel");
  if (cancel) {
    cancel.addEventListener("click", function () {
      fetch("/api/runs/" + encodeURIComponent(id) + "/cancel", { method: "POST" })
        .then(function (r) { return r.json(); }).then(function (info) { if (info.status) show(info); });
    });
  }
})();
