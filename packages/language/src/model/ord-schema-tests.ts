/**
 * The schema names written in ORD event tests: `ORD:0<ord_schema == "velocityLoop">` compares the
 * name ORD sends with a string, which names a schema without being a reference to it. The
 * validator checks that a schema has that name (supervisor-ord-schema-unknown) and a schema's
 * rename rewrites it (lsp/rename-edits.ts).
 */
import { AstUtils, type AstNode } from 'langium';
import { isEqualityTest, isModuleEvent, isStringLiteral, isVariableRef, type EqualityTest, type StringLiteral, type TestOperand } from '../generated/ast.js';

/**
 * The string an `ORD:n<ord_schema == "name">` test (`!=` too) compares with, when the other
 * operand is `ord_schema` itself; undefined for any other test.
 */
export function ordSchemaTestName(test: EqualityTest): StringLiteral | undefined {
    const isOrdSchema = (o: TestOperand | undefined): boolean => isVariableRef(o) && o.ordSchema && o.path.length === 0;
    const literal = isOrdSchema(test.left) ? test.right : isOrdSchema(test.right) ? test.left : undefined;
    if (!isStringLiteral(literal)) return undefined;
    return AstUtils.getContainerOfType(test, isModuleEvent)?.ord ? literal : undefined;
}

/** Every string of `root` that an ORD event test compares `ord_schema` with and that reads `name`. */
export function ordSchemaNamesIn(root: AstNode, name: string): StringLiteral[] {
    return AstUtils.streamAllContents(root).filter(isEqualityTest).map(ordSchemaTestName)
        .filter((l): l is StringLiteral => l !== undefined && l.value === name).toArray();
}
