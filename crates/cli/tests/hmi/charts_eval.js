// The chart view's transition conditions, evaluated as the page does
// (crates/online/hmi/charts.js, `SfcChart.compile`) outside a browser:
// run by crates/cli/tests/hmi.rs with Node.js. Prints `N passed, M failed`.
'use strict';
global.window = {};
require(process.argv[2]);
const compile = window.SfcChart.compile;
let passed = 0, failed = 0;
function check(name, got, want) {
  const ok = JSON.stringify(got) === JSON.stringify(want);
  if (ok) passed++; else failed++;
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${name}${ok ? '' : `: got ${JSON.stringify(got)}, want ${JSON.stringify(want)}`}`);
}
// The paths a program has (as the symbol tree gives them).
const have = (inst, names) => (n) => names.includes(n.toLowerCase()) ? `${inst}.${n}` : null;

const crane = have('Ctrl', ['gs5.t', 'dwell_time', 'l1', 'l2', 'pornire']);
const dwell = compile('GS5.t >= DWELL_TIME', crane);
check('crane dwell: watched paths', dwell.paths, ['Ctrl.GS5.t', 'Ctrl.DWELL_TIME']);
check('crane dwell: 2 s of 3 s not yet', dwell.value(new Map([['Ctrl.GS5.t', 'T#2s'], ['Ctrl.DWELL_TIME', 'T#3s']])), false);
check('crane dwell: 3 s can fire', dwell.value(new Map([['Ctrl.GS5.t', 'T#3s'], ['Ctrl.DWELL_TIME', 'T#3s']])), true);
const start = compile('Pornire AND l1 AND NOT l2', crane);
check('NOT/AND', start.value(new Map([['Ctrl.Pornire', 'TRUE'], ['Ctrl.l1', 'TRUE'], ['Ctrl.l2', 'FALSE']])), true);

// PL7: `%Xi.T` and `%Xi` are the step `_Xi` of the chart model.
const trains = have('Train1', ['_x1.t', '_x1.x', 'left1']);
const pl7 = compile('%X1.T >= T#2s', trains);
check('PL7 %X1.T: watched path', pl7.paths, ['Train1._X1.T']);
check('PL7 %X1.T: 1.5 s not yet', pl7.value(new Map([['Train1._X1.T', 'T#1s500ms']])), false);
check('PL7 %X1.T: 2.01 s can fire', pl7.value(new Map([['Train1._X1.T', 'T#2s10ms']])), true);
const both = compile('%X1 AND Left1', trains);
check('PL7 %X1 as activity', both.paths, ['Train1._X1.X', 'Train1.Left1']);

// What the page cannot evaluate is left unmarked, never guessed.
check('a call is not evaluated', compile('F(x) > 2', crane), null);
check('an unknown name is not evaluated', compile('nope', crane), null);

console.log(`${passed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
