/**
 * Named constants (`const int NJOINTS = 6;`, an extension of the report): the int a constant
 * stands for, following chains (`const int N = M;`) and stopping at cycles (reported by
 * validation as `const-cycle`).
 */
import { isConstant, isIntLiteral, isVariableRef, type Constant, type Value } from '../generated/ast.js';

/** The constants a constant's value refers to, in chain order, and whether the chain loops back. */
export function constantChain(start: Constant): { chain: Constant[]; cycle: boolean } {
    const chain: Constant[] = [];
    let current: Constant | undefined = start;
    while (current) {
        if (chain.includes(current)) return { chain: [...chain, current], cycle: true };
        chain.push(current);
        const value: Value = current.value;
        current = isVariableRef(value) && value.path.length === 0 && isConstant(value.variable?.ref) ? value.variable.ref : undefined;
    }
    return { chain, cycle: false };
}

/** The integer value of an int constant, or undefined (not an int, not a literal at the end of its chain, cyclic). */
export function constantInt(constant: Constant | undefined): number | undefined {
    if (!constant || constant.type?.primitive !== 'int' || constant.type.dimensions.length > 0) return undefined;
    const { chain, cycle } = constantChain(constant);
    if (cycle) return undefined;
    const last = chain[chain.length - 1]!.value;
    return isIntLiteral(last) ? last.value : undefined;
}
