// The demo's state in words, and the names and states its controls expose to assistive technology.
//
// This view shows the description under the demo's picture in a polite live region: an element
// that exists from the start and whose text changes only when the demo comes to rest, so a screen
// reader reads each new state once.  The same sentence is the picture's alt text.  It also gives
// the demo's ipywidgets controls what they lack: every slider its label as its name and the shown
// value as the value read out (a log slider's handle would say the exponent), every toggle and
// choice button its pressed state, and a group of choice buttons a name.  A slider's readout is
// taken out of the Tab order: the handle is the control, and it announces the readout's value.

function setAttr(el, name, value) {
  if (el.getAttribute(name) !== value) el.setAttribute(name, value);
}

// `names` maps each control's key (its CSS class is kf-control-<key>) to its name.
function label(demo, text, names) {
  const img = demo.querySelector("img.kf-figure");
  if (img && text && img.alt !== text) img.alt = text;
  for (const [key, name] of Object.entries(names)) {
    const control = demo.querySelector(`.kf-control-${key}`);
    if (!control) continue;
    const handle = control.querySelector(".noUi-handle");
    if (handle) {
      setAttr(handle, "aria-label", name);
      const readout = control.querySelector(".widget-readout");
      if (readout) {
        setAttr(handle, "aria-valuetext", readout.textContent.trim());
        setAttr(readout, "aria-label", `${name}, value`);
        setAttr(readout, "tabindex", "-1"); // text the handle announces, typed into with a click: no Tab stop
      }
    }
    if (control.classList.contains("widget-toggle-buttons")) {
      setAttr(control, "role", "group");
      setAttr(control, "aria-label", name);
    }
  }
  for (const button of demo.querySelectorAll("button.widget-toggle-button")) {
    setAttr(button, "aria-pressed", String(button.classList.contains("mod-active")));
  }
}

function render({ model, el }) {
  el.classList.add("kf-description");
  const region = document.createElement("p");
  region.setAttribute("aria-live", "polite");
  el.appendChild(region);
  let demo = null;
  let tries = 600;  // frames to wait for the demo around this view: ten seconds
  const update = () => {
    const text = model.get("text");
    if (region.textContent !== text) region.textContent = text;
    if (demo) label(demo, text, model.get("names"));
  };
  // A control's state shows in its classes, a slider's value in its readout and in the handle's
  // attributes (which the slider rewrites on every move): follow them all.
  const observer = new MutationObserver(update);
  const attach = () => {
    demo = el.closest(".kf-demo");
    if (!demo) {
      if (--tries > 0) requestAnimationFrame(attach);  // not yet in the page
      return;
    }
    observer.observe(demo, {
      subtree: true,
      childList: true,
      characterData: true,
      attributes: true,
      attributeFilter: ["class", "aria-valuetext"],
    });
    update();
  };
  model.on("change:text", update);
  model.on("change:names", update);
  attach();
  return () => {
    observer.disconnect();
    model.off("change:text", update);
    model.off("change:names", update);
  };
}

export default { render };
