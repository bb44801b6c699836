// The demo family's page script (served at /static/plugins/demo_bricks/bricks.js): it says
// how many bricks the server drew, read from the figure's data attribute.
document.addEventListener("DOMContentLoaded", () => {
  const wall = document.getElementById("wall");
  const count = document.getElementById("count");
  if (wall && count) count.textContent = wall.dataset.bricks + " bricks drawn";
});
