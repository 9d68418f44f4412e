/**
 * The machinery of the management service: loading implementations from the class path or from
 * allowlisted jars, and the class loader of a jar. Not exported.
 */
package io.etherware.services.management.internal;
