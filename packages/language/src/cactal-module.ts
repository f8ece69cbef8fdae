import { inject, type Module } from 'langium';
import {
    createDefaultModule, createDefaultSharedModule,
    type DefaultSharedModuleContext, type LangiumServices, type LangiumSharedServices, type PartialLangiumServices,
    type PartialLangiumSharedServices
} from 'langium/lsp';
import { CactalGeneratedModule, CactalGeneratedSharedModule } from './generated/module.js';
import { CactalDocumentFactory } from './parser/nesting-guard.js';
import { CactalParserErrorMessageProvider } from './parser/error-messages.js';
import { CactalLexer, createCactalParser } from './parser/keyword-repair.js';
import { CactalValueConverter } from './parser/value-converter.js';
import { CactalDocumentBuilder } from './scoping/cactal-document-builder.js';
import { CactalScopeProvider } from './scoping/cactal-scope-provider.js';
import { CactalScopeComputation } from './scoping/cactal-scope-computation.js';
import { ImportResolver } from './scoping/import-resolver.js';
import { CactalProjects } from './scoping/projects.js';
import { CactalDocumentValidator } from './validation/cactal-document-validator.js';
import { registerValidationChecks } from './validation/cactal-validator.js';
import { CactalLspModule } from './lsp/cactal-lsp-module.js';
import { CactalDocumentUpdateHandler } from './lsp/scenario/scenario-document-update-handler.js';

/** Services added by the Cactal language on top of Langium's. */
export type CactalAddedServices = {
    imports: {
        ImportResolver: ImportResolver
    },
    projects: {
        /** Which project a document belongs to (scoping/projects.ts). */
        Projects: CactalProjects
    }
};

/** All services of the Cactal language. */
export type CactalServices = LangiumServices & CactalAddedServices;

/** Cactal's own service implementations, bound over Langium's defaults. */
export const CactalModule: Module<CactalServices, PartialLangiumServices & CactalAddedServices> = {
    imports: {
        ImportResolver: (services) => new ImportResolver(services)
    },
    projects: {
        Projects: (services) => new CactalProjects(services.shared)
    },
    parser: {
        ParserErrorMessageProvider: () => new CactalParserErrorMessageProvider(),
        Lexer: (services) => new CactalLexer(services),
        LangiumParser: (services) => createCactalParser(services),
        ValueConverter: () => new CactalValueConverter()
    },
    references: {
        ScopeProvider: (services) => new CactalScopeProvider(services),
        ScopeComputation: (services) => new CactalScopeComputation(services)
    },
    validation: {
        DocumentValidator: (services) => new CactalDocumentValidator(services)
    }
};

/**
 * Shared-service overrides: the document factory guards the parser against pathological nesting;
 * the document builder revalidates a file when a file it imports changes; `.scenario` files are
 * kept out of the builder (the scenario support checks them: src/lsp/scenario/).
 */
export const CactalSharedModule: Module<LangiumSharedServices, PartialLangiumSharedServices> = {
    workspace: {
        LangiumDocumentFactory: (services) => new CactalDocumentFactory(services),
        DocumentBuilder: (services) => new CactalDocumentBuilder(services)
    },
    lsp: {
        DocumentUpdateHandler: (services) => new CactalDocumentUpdateHandler(services)
    }
};

/**
 * Creates the shared services and the Cactal services. `context` gives the file system
 * (`NodeFileSystem` from 'langium/node' in Node, `EmptyFileSystem` in a browser worker) and,
 * for a language server, the LSP connection. `extra` modules override or extend services
 * (the editor services are added this way).
 */
export function createCactalServices(
    context: DefaultSharedModuleContext,
    ...extra: Array<Module<CactalServices, PartialLangiumServices & Partial<CactalAddedServices>>>
): { shared: LangiumSharedServices; Cactal: CactalServices } {
    const shared = inject(createDefaultSharedModule(context), CactalGeneratedSharedModule, CactalSharedModule);
    const Cactal = (inject as (...modules: unknown[]) => CactalServices)(
        createDefaultModule({ shared }),
        CactalGeneratedModule,
        CactalModule,
        CactalLspModule,
        ...extra
    );
    shared.ServiceRegistry.register(Cactal);
    registerValidationChecks(Cactal);
    if (!context.connection) {
        // No language server: the workspace is built on demand and nothing waits for a client.
        shared.workspace.ConfigurationProvider.initialized({});
    }
    return { shared, Cactal };
}
