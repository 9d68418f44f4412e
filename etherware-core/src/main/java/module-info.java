/**
 * Etherware core: messages and their XML codec, the component model, the kernel with its
 * profile registry, and the scheduler SPI with the original FIFO dispatcher.
 */
module io.etherware.core {
    requires transitive org.slf4j;
    requires com.fasterxml.jackson.databind;
    requires com.fasterxml.jackson.dataformat.xml;

    exports io.etherware.core.component;
    exports io.etherware.core.kernel;
    exports io.etherware.core.message;
    exports io.etherware.core.scheduler;
    exports io.etherware.core.time;
}
