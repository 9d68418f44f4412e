/**
 * Etherware core: messages and their XML codec, the component model, the kernel with its
 * profile registry, and the scheduler SPI with the original FIFO dispatcher.
 *
 * <p>The codec reads contents records by reflection from this module: a public record in an
 * exported package needs nothing, any other record's package must be opened to
 * {@code io.etherware.core} (see {@link io.etherware.core.codec.MessageCodec}).
 */
module io.etherware.core {
    requires transitive org.slf4j;
    requires com.fasterxml.jackson.core;
    requires com.fasterxml.jackson.databind;
    requires com.fasterxml.jackson.dataformat.xml;
    // Woodstox is Jackson XML's StAX implementation; the codec configures it directly to harden it.
    requires com.ctc.wstx;
    requires org.codehaus.stax2;

    exports io.etherware.core.codec;
    exports io.etherware.core.component;
    exports io.etherware.core.kernel;
    exports io.etherware.core.message;
    exports io.etherware.core.scheduler;
    exports io.etherware.core.time;
}
