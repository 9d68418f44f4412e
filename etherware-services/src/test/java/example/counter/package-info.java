/**
 * Test components playing the role of user code for upgrades: deliberately outside the
 * {@code io.etherware} packages, which a jar's class loader always takes from the node.
 */
package example.counter;
