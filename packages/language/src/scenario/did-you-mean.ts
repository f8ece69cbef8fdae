/**
 * "Did you mean" for a misspelt name in a scenario (docs/simulation.md "Values and names"): the
 * closest known name by edit distance (letters swapped, missing, extra or wrong; case ignored),
 * only when it is close enough that it is likely the intended one. The distance and the rule are
 * those of every "Did you mean" of the language (model/near-names.ts).
 */
import { closestName } from '../model/near-names.js';

export { closestName, editDistance } from '../model/near-names.js';

/** `. Did you mean 'X'?` or the empty string. */
export function didYouMean(name: string, known: Iterable<string>): string {
    const best = closestName(name, known);
    return best === undefined ? '' : `. Did you mean '${best}'?`;
}
