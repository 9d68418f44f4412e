package io.etherware.core.codec;

import org.xml.sax.SAXException;

import javax.xml.XMLConstants;
import javax.xml.transform.stream.StreamSource;
import javax.xml.validation.Schema;
import javax.xml.validation.SchemaFactory;
import java.io.ByteArrayInputStream;
import java.io.IOException;
import java.io.UncheckedIOException;
import java.net.URL;

/** The shipped envelope schema, loaded from the codec's resources as a peer would use it. */
final class Schemas {

    static final String RESOURCE = "/io/etherware/core/codec/etherware-message.xsd";

    private static final Schema SCHEMA = load();

    private Schemas() {
    }

    private static Schema load() {
        URL xsd = MessageCodec.class.getResource(RESOURCE);
        if (xsd == null) {
            throw new IllegalStateException(RESOURCE + " is not on the class path");
        }
        try {
            var factory = SchemaFactory.newInstance(XMLConstants.W3C_XML_SCHEMA_NS_URI);
            factory.setProperty(XMLConstants.ACCESS_EXTERNAL_DTD, "");
            factory.setProperty(XMLConstants.ACCESS_EXTERNAL_SCHEMA, "");
            return factory.newSchema(xsd);
        } catch (SAXException e) {
            throw new IllegalStateException("etherware-message.xsd is not a valid schema: " + e.getMessage(), e);
        }
    }

    /** Validates a document; throws {@link SAXException} with the validator's reason if it is invalid. */
    static void validate(byte[] document) throws SAXException {
        try {
            var validator = SCHEMA.newValidator();
            validator.setProperty(XMLConstants.ACCESS_EXTERNAL_DTD, "");
            validator.setProperty(XMLConstants.ACCESS_EXTERNAL_SCHEMA, "");
            validator.validate(new StreamSource(new ByteArrayInputStream(document)));
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }
}
