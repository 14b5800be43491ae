/* rsm-lrg notebook profiler, inside its sandboxed frame: asks the notebook page (the frame's
 * parent) for the shared assets (plotly.js, the page's script and style), which the first
 * profiler displayed in the kernel session carried into the notebook once, and inserts them.
 * A script runs only when its SHA-256 is one the frame's Content-Security-Policy names, so
 * the text that arrives must be exactly the expected one. */
(function () {
  "use strict";
  var NEED = JSON.parse(document.getElementById("rsm-assets").textContent);  /* [[kind, hex sha-256], ...] */
  var done = false, tries = 0;
  function note(text) {
    var p = document.createElement("p");
    p.className = "note"; p.id = "assets-missing"; p.textContent = text;
    document.body.insertBefore(p, document.body.firstChild);
  }
  window.addEventListener("message", function (ev) {
    var d = ev.data;
    if (done || ev.source !== window.parent || !d || d.type !== "rsm-lrg-assets" || typeof d.assets !== "object") return;
    for (var i = 0; i < NEED.length; i++) if (typeof d.assets[NEED[i][1]] !== "string") return;
    done = true;
    NEED.forEach(function (a) {
      var el = document.createElement(a[0] === "css" ? "style" : "script");
      el.textContent = d.assets[a[1]];
      document.head.appendChild(el);
    });
    if (typeof window.Plotly === "undefined" || !window.rsmReport)
      note("plotly.js or the page's script arrived altered and was refused (its SHA-256 is not the expected " +
           "one): is the notebook page read as UTF-8? Save the profiler with .save(path) and open the file.");
  });
  function ask() {
    if (done) return;
    if (tries++ >= 40) {
      note("plotly.js and the page's script did not arrive from the notebook: the output that carried them " +
           "is gone, or the notebook does not run scripts in outputs. Run " +
           "rsm_lrg.report.interactive.notebook_reset() and display the profiler again, or save it " +
           "with .save(path) and open the file.");
      return;
    }
    window.parent.postMessage({type: "rsm-lrg-assets-request", need: NEED.map(function (a) { return a[1]; })}, "*");
    setTimeout(ask, 250);
  }
  ask();
})();
