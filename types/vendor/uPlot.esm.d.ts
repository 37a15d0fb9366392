// The page imports uPlot from vendor/ (copied there by scripts/build from
// node_modules/uplot/dist); its types are the npm package's own.
import uPlot from 'uplot';
export default uPlot;
