// Opens an HTML report in the machine's Chromium (headless, no network): fails on a console
// error, a page error or an image that did not load, and writes a screenshot.
//   node tests/browser/report.mjs REPORT.html SCREENSHOT.png
import { chromium } from "playwright-core";
import { pathToFileURL } from "node:url";

const [page_path, screenshot] = process.argv.slice(2);
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
  // Without these, Chromium tries the network at start-up, which a closed machine refuses.
  args: ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"],
});
const problems = [];
const page = await browser.newPage({ viewport: { width: 1280, height: 900 } });
page.on("console", (m) => { if (m.type() === "error") problems.push(`console: ${m.text()}`); });
page.on("pageerror", (e) => problems.push(`page error: ${e.message}`));
page.on("requestfailed", (r) => problems.push(`request failed: ${r.url().slice(0, 80)}`));
page.on("request", (r) => {
  if (!r.url().startsWith("file:") && !r.url().startsWith("data:")) problems.push(`fetched: ${r.url()}`);
});
await page.goto(pathToFileURL(page_path).href, { waitUntil: "load" });
const images = await page.$$eval("img", (all) => all.map((i) => ({ ok: i.complete && i.naturalWidth > 0, alt: i.alt })));
const broken = images.filter((i) => !i.ok);
broken.forEach((i) => problems.push(`broken image: ${i.alt}`));
const scripts = await page.$$eval("script", (s) => s.length);
if (scripts > 0) problems.push(`${scripts} script element(s): the page must work without JavaScript`);
await page.screenshot({ path: screenshot, fullPage: false });
await browser.close();
console.log(`${images.length} images, ${broken.length} broken; ${problems.length} problem(s); screenshot ${screenshot}`);
if (problems.length > 0) {
  console.error(problems.slice(0, 20).join("\n"));
  process.exit(1);
}
